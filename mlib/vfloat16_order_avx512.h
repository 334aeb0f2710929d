// mlib/vfloat16_order_avx512.h — compress_in_order for vfloat16 on AVX-512 (F, DQ): the
// sixteen-lane sibling of vfloat8_order_avx512.h (see vfloat8_order_avx2.h for what it
// does). Position j names lane (order[j] >> shift) & 15: four bits per order, where the
// eight-lane forms read three.
#pragma once

#include <immintrin.h>

#include <bit>
#include <cstdint>

#include "mlib/vfloat16_avx512.h"

#if !defined(__AVX512F__) || !defined(__AVX512DQ__)
#error "mlib/vfloat16_order_avx512.h needs AVX-512 F and DQ"
#endif

namespace mlib {
inline namespace avx512_order {

MLIB_INLINE int compress_in_order(vfloat16 t, const std::uint32_t* ids, const std::uint32_t* order,
                                  int shift, unsigned hit, float* t_out, std::uint32_t* id_out) {
  // permutexvar reads the low four bits of each index: the fields above need no mask.
  const __m512i idx = _mm512_srl_epi32(_mm512_loadu_si512(order), _mm_cvtsi32_si128(shift));
  const __m512i selected = _mm512_maskz_mov_epi32(__mmask16(hit), _mm512_set1_epi32(-1));
  const __mmask16 at = _mm512_movepi32_mask(_mm512_permutexvar_epi32(idx, selected));
  _mm512_storeu_ps(t_out, _mm512_maskz_compress_ps(at, _mm512_permutexvar_ps(idx, t.v)));
  _mm512_storeu_si512(id_out, _mm512_maskz_compress_epi32(
                                  at, _mm512_permutexvar_epi32(idx, _mm512_loadu_si512(ids))));
  return std::popcount(hit & 0xffffu);
}

}  // namespace avx512_order
}  // namespace mlib
