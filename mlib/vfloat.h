// mlib/vfloat.h — vfloat<N>: N independent float lanes for structure-of-arrays code, mapped
// onto the widest type the translation unit was compiled for. N = 4: vfloat4 (SSE4.1, or
// plain C++ in the scalar build); N = 8: vfloat8 (AVX2, also used by AVX-512 units); N = 16:
// vfloat16 (AVX-512 units).
//
// The translation units that include this are built once per instruction set (rt2/base/isa.h);
// the rest of the program stays at the portable baseline.
#pragma once

#if defined(MLIB_SCALAR)
#include "mlib/vfloat4_scalar.h"
#else
#include "mlib/vfloat4_sse41.h"
#endif
#if defined(__AVX2__) && !defined(MLIB_SCALAR)
#include "mlib/vfloat8_avx2.h"
#endif
#if defined(__AVX512F__) && !defined(MLIB_SCALAR)
#include "mlib/vfloat16_avx512.h"
#endif
// compress_in_order(vfloat8, ...) and (vfloat16, ...): one file per instruction set.
#if defined(__AVX512VL__) && defined(__AVX512DQ__) && !defined(MLIB_SCALAR)
#include "mlib/vfloat8_order_avx512.h"
#include "mlib/vfloat16_order_avx512.h"
#elif defined(__AVX2__) && !defined(MLIB_SCALAR)
#include "mlib/vfloat8_order_avx2.h"
#endif

namespace mlib {

template <int N>
struct vfloat_select;
template <>
struct vfloat_select<4> {
  using type = vfloat4;
};
#if defined(__AVX2__) && !defined(MLIB_SCALAR)
template <>
struct vfloat_select<8> {
  using type = vfloat8;
};
#endif
#if defined(__AVX512F__) && !defined(MLIB_SCALAR)
template <>
struct vfloat_select<16> {
  using type = vfloat16;
};
#endif

// The widest vfloat this translation unit has.
#if defined(__AVX512F__) && !defined(MLIB_SCALAR)
inline constexpr int kWidestLanes = 16;
#elif defined(__AVX2__) && !defined(MLIB_SCALAR)
inline constexpr int kWidestLanes = 8;
#else
inline constexpr int kWidestLanes = 4;
#endif

template <int N>
using vfloat = typename vfloat_select<N>::type;

}  // namespace mlib
