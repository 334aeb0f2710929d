// mlib/vfloat8_avx2.h — vfloat8 / vbool8: eight independent float lanes on AVX2, the
// sibling of vfloat4_sse41.h with the same API (see there). Included only by the
// translation units built for AVX2 or AVX-512 (rt2/base/isa.h).
#pragma once

#include <immintrin.h>

#include <array>
#include <cstdint>

#include "mlib/simd.h"  // MLIB_INLINE
#include "mlib/vfloat4_sse41.h"

#if !defined(__AVX2__)
#error "mlib/vfloat8_avx2.h needs AVX2: include it only from a translation unit built for it"
#endif

namespace mlib {

struct vbool8 {
  __m256 m;
  static constexpr int size = 8;
  // Lane i set where bit i of `b` is.
  MLIB_INLINE static vbool8 from_bits(unsigned b) {
    const __m256i bit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    const __m256i set = _mm256_and_si256(_mm256_set1_epi32(static_cast<int>(b)), bit);
    return {_mm256_castsi256_ps(_mm256_cmpeq_epi32(set, bit))};
  }
};

struct vfloat8 {
  __m256 v;
  static constexpr int size = 8;
  using bool_type = vbool8;

  MLIB_INLINE static vfloat8 broadcast(float s) { return {_mm256_set1_ps(s)}; }
  MLIB_INLINE static vfloat8 load(const float* p) { return {_mm256_load_ps(p)}; }  // 32-byte aligned
  MLIB_INLINE void store(float* p) const { _mm256_store_ps(p, v); }
  MLIB_INLINE static vfloat8 loadu(const void* p) { return {_mm256_loadu_ps(static_cast<const float*>(p))}; }
  MLIB_INLINE void storeu(void* p) const { _mm256_storeu_ps(static_cast<float*>(p), v); }
  // Lane i = p[i] as a float (8 bytes, any alignment).
  MLIB_INLINE static vfloat8 from_bytes(const std::uint8_t* p) {
    return {_mm256_cvtepi32_ps(_mm256_cvtepu8_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(p))))};
  }
  // lo[0 ... 3] in lanes 0 ... 3 and hi[0 ... 3] in lanes 4 ... 7 (each 16-byte aligned).
  MLIB_INLINE static vfloat8 load_halves(const float* lo, const float* hi) {
    return {_mm256_insertf128_ps(_mm256_castps128_ps256(_mm_load_ps(lo)), _mm_load_ps(hi), 1)};
  }
  // lo's lanes in lanes 0 ... 3 and hi's in 4 ... 7.
  MLIB_INLINE static vfloat8 from_halves(vfloat4 lo, vfloat4 hi) {
    return {_mm256_set_m128(hi.v, lo.v)};
  }
  // p[0 ... 3] in every four lanes.
  MLIB_INLINE static vfloat8 broadcast_quad(const float* p) {
    return {_mm256_broadcast_ps(reinterpret_cast<const __m128*>(p))};
  }
  // Lane i = src[ids[i / 4]] (see vfloat16_avx512.h): two rays' values over four lanes each.
  MLIB_INLINE static vfloat8 spread_quads(const float* src, const std::uint32_t* ids) {
    return {_mm256_set_m128(_mm_broadcast_ss(src + ids[1]), _mm_broadcast_ss(src + ids[0]))};
  }
};

MLIB_INLINE vfloat8 operator+(vfloat8 a, vfloat8 b) { return {_mm256_add_ps(a.v, b.v)}; }
MLIB_INLINE vfloat8 operator-(vfloat8 a, vfloat8 b) { return {_mm256_sub_ps(a.v, b.v)}; }
MLIB_INLINE vfloat8 operator*(vfloat8 a, vfloat8 b) { return {_mm256_mul_ps(a.v, b.v)}; }
// a * b + c rounded once (FMA; the units built for AVX2 have it): only where a caller asks
// for it by name, as the build forbids contracting a * b + c on its own.
MLIB_INLINE vfloat8 fmadd(vfloat8 a, vfloat8 b, vfloat8 c) { return {_mm256_fmadd_ps(a.v, b.v, c.v)}; }
MLIB_INLINE vfloat8 operator/(vfloat8 a, vfloat8 b) { return {_mm256_div_ps(a.v, b.v)}; }
MLIB_INLINE vfloat8 min(vfloat8 a, vfloat8 b) { return {_mm256_min_ps(a.v, b.v)}; }
MLIB_INLINE vfloat8 max(vfloat8 a, vfloat8 b) { return {_mm256_max_ps(a.v, b.v)}; }
MLIB_INLINE vfloat8 abs(vfloat8 a) { return {_mm256_andnot_ps(_mm256_set1_ps(-0.0f), a.v)}; }
MLIB_INLINE vfloat8 sqrt(vfloat8 a) { return {_mm256_sqrt_ps(a.v)}; }  // correctly rounded
MLIB_INLINE vfloat8 floor(vfloat8 a) { return {_mm256_floor_ps(a.v)}; }
MLIB_INLINE vfloat8 step_ulps(vfloat8 a, vfloat8 k) {  // see mlib/simd.h
  const __m256i steps = _mm256_cvttps_epi32(k.v);
  const __m256i negative = _mm256_castps_si256(_mm256_cmp_ps(a.v, _mm256_setzero_ps(), _CMP_LT_OQ));
  const __m256i signed_steps = _mm256_sub_epi32(_mm256_xor_si256(steps, negative), negative);
  return {_mm256_castsi256_ps(_mm256_add_epi32(_mm256_castps_si256(a.v), signed_steps))};
}
MLIB_INLINE vfloat8 xor_sign(vfloat8 a, vfloat8 s) {
  return {_mm256_xor_ps(a.v, _mm256_and_ps(s.v, _mm256_set1_ps(-0.0f)))};
}

MLIB_INLINE vbool8 operator<(vfloat8 a, vfloat8 b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_LT_OQ)}; }
MLIB_INLINE vbool8 operator<=(vfloat8 a, vfloat8 b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_LE_OQ)}; }
MLIB_INLINE vbool8 operator>(vfloat8 a, vfloat8 b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_GT_OQ)}; }
MLIB_INLINE vbool8 operator>=(vfloat8 a, vfloat8 b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_GE_OQ)}; }
MLIB_INLINE vbool8 operator==(vfloat8 a, vfloat8 b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_EQ_OQ)}; }
MLIB_INLINE vbool8 operator!=(vfloat8 a, vfloat8 b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_NEQ_UQ)}; }  // true for NaN
MLIB_INLINE vbool8 operator&(vbool8 a, vbool8 b) { return {_mm256_and_ps(a.m, b.m)}; }
MLIB_INLINE vbool8 operator|(vbool8 a, vbool8 b) { return {_mm256_or_ps(a.m, b.m)}; }
MLIB_INLINE vbool8 andnot(vbool8 a, vbool8 b) { return {_mm256_andnot_ps(a.m, b.m)}; }  // ~a & b

// See vfloat4_sse41.h.
MLIB_INLINE vfloat8 imin(vfloat8 a, vfloat8 b) {
  return {_mm256_castsi256_ps(_mm256_min_epi32(_mm256_castps_si256(a.v), _mm256_castps_si256(b.v)))};
}
MLIB_INLINE vfloat8 imax(vfloat8 a, vfloat8 b) {
  return {_mm256_castsi256_ps(_mm256_max_epi32(_mm256_castps_si256(a.v), _mm256_castps_si256(b.v)))};
}
MLIB_INLINE vbool8 ile(vfloat8 a, vfloat8 b) {
  const __m256i gt = _mm256_cmpgt_epi32(_mm256_castps_si256(a.v), _mm256_castps_si256(b.v));
  return {_mm256_castsi256_ps(_mm256_xor_si256(gt, _mm256_set1_epi32(-1)))};
}

MLIB_INLINE vfloat8 select(vbool8 m, vfloat8 if_true, vfloat8 if_false) {
  return {_mm256_blendv_ps(if_false.v, if_true.v, m.m)};
}
MLIB_INLINE unsigned bits(vbool8 m) { return static_cast<unsigned>(_mm256_movemask_ps(m.m)); }

namespace detail {
// Per 8-bit mask, the lanes it selects in order, a lane index per nibble (then zeros).
constexpr std::array<std::uint32_t, 256> compress8_table() {
  std::array<std::uint32_t, 256> t{};
  for (unsigned m = 0; m < 256; ++m) {
    unsigned k = 0;
    for (unsigned i = 0; i < 8; ++i)
      if (m >> i & 1) t[m] |= i << (4 * k++);
  }
  return t;
}
inline constexpr std::array<std::uint32_t, 256> kCompress8 = compress8_table();
}  // namespace detail

// The lanes of `m` set, in order, moved to the lowest lanes (see vfloat16_avx512.h).
MLIB_INLINE vfloat8 compress(vfloat8 a, unsigned m) {
  const __m256i nibbles = _mm256_set1_epi32(static_cast<int>(detail::kCompress8[m & 0xFFu]));
  const __m256i idx = _mm256_and_si256(
      _mm256_srlv_epi32(nibbles, _mm256_setr_epi32(0, 4, 8, 12, 16, 20, 24, 28)), _mm256_set1_epi32(7));
  return {_mm256_permutevar8x32_ps(a.v, idx)};
}


MLIB_INLINE vfloat8 reduce_min(vfloat8 a) {
  __m256 m = _mm256_min_ps(a.v, _mm256_permute_ps(a.v, _MM_SHUFFLE(2, 3, 0, 1)));
  m = _mm256_min_ps(m, _mm256_permute_ps(m, _MM_SHUFFLE(1, 0, 3, 2)));
  return {_mm256_min_ps(m, _mm256_permute2f128_ps(m, m, 0x01))};
}
MLIB_INLINE vfloat8 reduce_max(vfloat8 a) {
  __m256 m = _mm256_max_ps(a.v, _mm256_permute_ps(a.v, _MM_SHUFFLE(2, 3, 0, 1)));
  m = _mm256_max_ps(m, _mm256_permute_ps(m, _MM_SHUFFLE(1, 0, 3, 2)));
  return {_mm256_max_ps(m, _mm256_permute2f128_ps(m, m, 0x01))};
}

}  // namespace mlib
