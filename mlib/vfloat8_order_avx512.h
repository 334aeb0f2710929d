// mlib/vfloat8_order_avx512.h — compress_in_order for vfloat8 on AVX-512 (VL, DQ): the
// sibling of vfloat8_order_avx2.h (see there for what it does), with the compress
// instructions in place of the table and permute.
#pragma once

#include <immintrin.h>

#include <bit>
#include <cstdint>

#include "mlib/vfloat8_avx2.h"

#if !defined(__AVX512VL__) || !defined(__AVX512DQ__)
#error "mlib/vfloat8_order_avx512.h needs AVX-512 VL and DQ"
#endif

namespace mlib {
inline namespace avx512_order {

MLIB_INLINE int compress_in_order(vfloat8 t, const std::uint32_t* ids, const std::uint32_t* order,
                                  int shift, unsigned hit, float* t_out, std::uint32_t* id_out) {
  const __m256i idx =
      _mm256_srl_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(order)),
                       _mm_cvtsi32_si128(shift));
  const __m256i selected = _mm256_maskz_mov_epi32(__mmask8(hit), _mm256_set1_epi32(-1));
  const __mmask8 at = _mm256_movepi32_mask(_mm256_permutevar8x32_epi32(selected, idx));
  _mm256_storeu_ps(t_out, _mm256_maskz_compress_ps(at, _mm256_permutevar8x32_ps(t.v, idx)));
  _mm256_storeu_si256(
      reinterpret_cast<__m256i*>(id_out),
      _mm256_maskz_compress_epi32(
          at, _mm256_permutevar8x32_epi32(
                  _mm256_loadu_si256(reinterpret_cast<const __m256i*>(ids)), idx)));
  return std::popcount(hit & 0xffu);
}

}  // namespace avx512_order
}  // namespace mlib
