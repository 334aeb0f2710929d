// mlib/vfloat8_order_avx2.h — compress_in_order for vfloat8 on AVX2: the lanes a mask
// selects, in a given order, written without gaps. Its sibling for AVX-512
// (vfloat8_order_avx512.h) does the same with the compress instructions; mlib/vfloat.h
// includes the one the translation unit was built for. Each lives in an inline namespace
// of its own, so the two never share a symbol (both are called as mlib::compress_in_order).
#pragma once

#include <immintrin.h>

#include <bit>
#include <cstdint>

#include "mlib/vfloat8_avx2.h"

#if !defined(__AVX2__)
#error "mlib/vfloat8_order_avx2.h needs AVX2: include it only from a translation unit built for it"
#endif

namespace mlib {
inline namespace avx2_order {

// For each 8-bit mask, the indices of its set bits packed into bytes from the lowest one
// (a table, not pdep / pext: those are microcoded and slow on AMD before Zen 3). 2 KiB. A
// plain array in a struct, not std::array: no library template gets instantiated in a
// unit built for AVX2, where the linker could pick its copy for the portable code.
struct PackedLanes {
  std::uint64_t of[256];
};
inline constexpr PackedLanes kPackedLanes = [] {
  PackedLanes table{};
  for (unsigned mask = 0; mask < 256; ++mask) {
    int k = 0;
    for (unsigned lane = 0; lane < 8; ++lane)
      if (mask >> lane & 1u) table.of[mask] |= std::uint64_t(lane) << (8 * k++);
  }
  return table;
}();

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
  // The selected positions packed to the front, then the lanes they name.
  const __m256i from = _mm256_permutevar8x32_epi32(
      idx, _mm256_cvtepu8_epi32(_mm_cvtsi64_si128(static_cast<long long>(kPackedLanes.of[at]))));
  _mm256_storeu_ps(t_out, _mm256_permutevar8x32_ps(t.v, from));
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(id_out),
                      _mm256_permutevar8x32_epi32(
                          _mm256_loadu_si256(reinterpret_cast<const __m256i*>(ids)), from));
  return std::popcount(hit & 0xffu);
}

}  // namespace avx2_order
}  // namespace mlib
