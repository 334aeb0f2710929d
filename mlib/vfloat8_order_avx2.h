// mlib/vfloat8_order_avx2.h — compress_in_order for vfloat8 on AVX2 (with BMI2): the lanes
// a mask selects, in a given order, written without gaps. Its sibling for AVX-512
// (vfloat8_order_avx512.h) does the same with the compress instructions; mlib/vfloat.h
// includes the one the translation unit was built for.
#pragma once

#include <immintrin.h>

#include <bit>
#include <cstdint>

#include "mlib/vfloat8_avx2.h"

#if !defined(__AVX2__) || !defined(__BMI2__)
#error "mlib/vfloat8_order_avx2.h needs AVX2 and BMI2"
#endif

namespace mlib {

// The lanes of `t`, and of the eight integers at `ids`, that `hit` selects (bit i: lane i),
// in the order `order` lists them: position j names lane (order[j] >> shift) & 7 (order
// holds a permutation of 0 ... 7 in every 3-bit field it is read at). Written to t_out
// and id_out without gaps, in that order; all eight lanes of both are stored (those past
// the count hold anything), so both need room for eight. Returns the count, popcount(hit).
MLIB_INLINE int compress_in_order(vfloat8 t, const std::uint32_t* ids, const std::uint32_t* order,
                                  int shift, unsigned hit, float* t_out, std::uint32_t* id_out) {
  // Position j's lane (only the low three bits count: permutevar reads no more).
  const __m256i idx =
      _mm256_srl_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(order)),
                       _mm_cvtsi32_si128(shift));
  // Which positions hold a selected lane.
  const __m256i bit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
  const __m256i selected =
      _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(int(hit)), bit), bit);
  const auto at = static_cast<unsigned>(
      _mm256_movemask_ps(_mm256_castsi256_ps(_mm256_permutevar8x32_epi32(selected, idx))));
  // The selected positions, packed to the front: one byte each, by pdep and pext.
  const std::uint64_t bytes = _pdep_u64(at, 0x0101010101010101ull) * 0xffu;
  const std::uint64_t packed = _pext_u64(0x0706050403020100ull, bytes);
  const __m256i from = _mm256_permutevar8x32_epi32(
      idx, _mm256_cvtepu8_epi32(_mm_cvtsi64_si128(static_cast<long long>(packed))));
  _mm256_storeu_ps(t_out, _mm256_permutevar8x32_ps(t.v, from));
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(id_out),
                      _mm256_permutevar8x32_epi32(
                          _mm256_loadu_si256(reinterpret_cast<const __m256i*>(ids)), from));
  return std::popcount(hit & 0xffu);
}

}  // namespace mlib
