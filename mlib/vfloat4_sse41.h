// mlib/vfloat4_sse41.h — vfloat4 / vbool4: four independent float lanes on SSE4.1, for
// structure-of-arrays code (four boxes, four triangles at a time).
//
// Unlike vec4 (one point or direction, lanes x y z w), a vfloat4's lanes are four unrelated
// values. The API is shared with the sibling files vfloat8_avx2.h (eight lanes) and
// vfloat4_scalar.h (plain C++), so code templated on the width compiles against any of
// them. Only the translation units built for an ISA include the wide files (rt2/base/isa.h).
//
// NaN conventions (callers rely on them): min(a, b) / max(a, b) return b in a lane where
// either operand is NaN; ordered comparisons are false in a NaN lane.
#pragma once

#include <smmintrin.h>  // SSE4.1

#include <array>
#include <cstdint>
#include <cstring>

#include "mlib/simd.h"  // MLIB_INLINE

namespace mlib {

struct vbool4 {
  __m128 m;
  static constexpr int size = 4;
  // Lane i set where bit i of `b` is.
  MLIB_INLINE static vbool4 from_bits(unsigned b) {
    const __m128i bit = _mm_setr_epi32(1, 2, 4, 8);
    const __m128i set = _mm_and_si128(_mm_set1_epi32(static_cast<int>(b)), bit);
    return {_mm_castsi128_ps(_mm_cmpeq_epi32(set, bit))};
  }
};

struct vfloat4 {
  __m128 v;
  static constexpr int size = 4;
  using bool_type = vbool4;

  MLIB_INLINE static vfloat4 broadcast(float s) { return {_mm_set1_ps(s)}; }
  MLIB_INLINE static vfloat4 load(const float* p) { return {_mm_load_ps(p)}; }  // 16-byte aligned
  MLIB_INLINE void store(float* p) const { _mm_store_ps(p, v); }
  MLIB_INLINE static vfloat4 loadu(const void* p) { return {_mm_loadu_ps(static_cast<const float*>(p))}; }  // any alignment
  MLIB_INLINE void storeu(void* p) const { _mm_storeu_ps(static_cast<float*>(p), v); }
  // Lane i = p[i] as a float (4 bytes, any alignment).
  MLIB_INLINE static vfloat4 from_bytes(const std::uint8_t* p) {
    std::int32_t bytes;
    std::memcpy(&bytes, p, sizeof bytes);
    return {_mm_cvtepi32_ps(_mm_cvtepu8_epi32(_mm_cvtsi32_si128(bytes)))};
  }
  MLIB_INLINE static vfloat4 broadcast_quad(const float* p) { return loadu(p); }  // see vfloat16_avx512.h
  // Lane i = src[ids[i / 4]] (see vfloat16_avx512.h): one ray's value in every lane.
  MLIB_INLINE static vfloat4 spread_quads(const float* src, const std::uint32_t* ids) {
    return broadcast(src[ids[0]]);
  }
  // From and to simd.h's four floats (vec4's lanes), without a trip through memory.
  MLIB_INLINE static vfloat4 from_f4(simd::f4 a) { return {a}; }
  MLIB_INLINE simd::f4 to_f4() const { return v; }
};

MLIB_INLINE vfloat4 operator+(vfloat4 a, vfloat4 b) { return {_mm_add_ps(a.v, b.v)}; }
MLIB_INLINE vfloat4 operator-(vfloat4 a, vfloat4 b) { return {_mm_sub_ps(a.v, b.v)}; }
MLIB_INLINE vfloat4 operator*(vfloat4 a, vfloat4 b) { return {_mm_mul_ps(a.v, b.v)}; }
MLIB_INLINE vfloat4 operator/(vfloat4 a, vfloat4 b) { return {_mm_div_ps(a.v, b.v)}; }
MLIB_INLINE vfloat4 min(vfloat4 a, vfloat4 b) { return {_mm_min_ps(a.v, b.v)}; }
MLIB_INLINE vfloat4 max(vfloat4 a, vfloat4 b) { return {_mm_max_ps(a.v, b.v)}; }
MLIB_INLINE vfloat4 abs(vfloat4 a) { return {_mm_andnot_ps(_mm_set1_ps(-0.0f), a.v)}; }
MLIB_INLINE vfloat4 sqrt(vfloat4 a) { return {_mm_sqrt_ps(a.v)}; }  // correctly rounded
// Rounded toward -inf (exact; NaN stays NaN).
MLIB_INLINE vfloat4 floor(vfloat4 a) { return {_mm_floor_ps(a.v)}; }
// Each lane's bits plus trunc(k), or minus it where a < 0 (mlib/simd.h, step_ulps).
MLIB_INLINE vfloat4 step_ulps(vfloat4 a, vfloat4 k) { return {simd::step_ulps(a.v, k.v)}; }
// The sign bit of each lane of `a` flipped where `s` is negative (or -0): a * sign(s)
// without a multiply.
MLIB_INLINE vfloat4 xor_sign(vfloat4 a, vfloat4 s) {
  return {_mm_xor_ps(a.v, _mm_and_ps(s.v, _mm_set1_ps(-0.0f)))};
}

MLIB_INLINE vbool4 operator<(vfloat4 a, vfloat4 b) { return {_mm_cmplt_ps(a.v, b.v)}; }
MLIB_INLINE vbool4 operator<=(vfloat4 a, vfloat4 b) { return {_mm_cmple_ps(a.v, b.v)}; }
MLIB_INLINE vbool4 operator>(vfloat4 a, vfloat4 b) { return {_mm_cmpgt_ps(a.v, b.v)}; }
MLIB_INLINE vbool4 operator>=(vfloat4 a, vfloat4 b) { return {_mm_cmpge_ps(a.v, b.v)}; }
MLIB_INLINE vbool4 operator==(vfloat4 a, vfloat4 b) { return {_mm_cmpeq_ps(a.v, b.v)}; }
MLIB_INLINE vbool4 operator!=(vfloat4 a, vfloat4 b) { return {_mm_cmpneq_ps(a.v, b.v)}; }  // true for NaN
MLIB_INLINE vbool4 operator&(vbool4 a, vbool4 b) { return {_mm_and_ps(a.m, b.m)}; }
MLIB_INLINE vbool4 operator|(vbool4 a, vbool4 b) { return {_mm_or_ps(a.m, b.m)}; }
MLIB_INLINE vbool4 andnot(vbool4 a, vbool4 b) { return {_mm_andnot_ps(a.m, b.m)}; }  // ~a & b

// Minimum, maximum and <= of the lanes' bit patterns read as signed integers. For floats
// that are not NaN this is the float order among non-negative values (+0 included) and
// puts every negative value below every non-negative one (-0 included, as the most negative
// integer). One cycle each, against four for minps / maxps / cmpps: the BVH's node test uses
// them where a non-negative bound (t_min, t_max) is among the operands.
MLIB_INLINE vfloat4 imin(vfloat4 a, vfloat4 b) {
  return {_mm_castsi128_ps(_mm_min_epi32(_mm_castps_si128(a.v), _mm_castps_si128(b.v)))};
}
MLIB_INLINE vfloat4 imax(vfloat4 a, vfloat4 b) {
  return {_mm_castsi128_ps(_mm_max_epi32(_mm_castps_si128(a.v), _mm_castps_si128(b.v)))};
}
MLIB_INLINE vbool4 ile(vfloat4 a, vfloat4 b) {
  const __m128i gt = _mm_cmpgt_epi32(_mm_castps_si128(a.v), _mm_castps_si128(b.v));
  return {_mm_castsi128_ps(_mm_xor_si128(gt, _mm_set1_epi32(-1)))};
}

// Lane i of the result is b's where m is set, else a's.
MLIB_INLINE vfloat4 select(vbool4 m, vfloat4 if_true, vfloat4 if_false) {
  return {_mm_blendv_ps(if_false.v, if_true.v, m.m)};
}
// Bit i set when lane i of m is.
MLIB_INLINE unsigned bits(vbool4 m) { return static_cast<unsigned>(_mm_movemask_ps(m.m)); }

namespace detail {
// Per 4-bit mask, the byte shuffle that moves the lanes it selects, in order, to the lowest
// lanes (then lane 0's bytes again).
constexpr std::array<std::array<std::uint8_t, 16>, 16> compress4_table() {
  std::array<std::array<std::uint8_t, 16>, 16> t{};
  for (unsigned m = 0; m < 16; ++m) {
    unsigned k = 0;
    for (unsigned i = 0; i < 4; ++i)
      if (m >> i & 1) {
        for (unsigned b = 0; b < 4; ++b) t[m][4 * k + b] = static_cast<std::uint8_t>(4 * i + b);
        ++k;
      }
    for (; k < 4; ++k)
      for (unsigned b = 0; b < 4; ++b) t[m][4 * k + b] = static_cast<std::uint8_t>(b);
  }
  return t;
}
inline constexpr std::array<std::array<std::uint8_t, 16>, 16> kCompress4 = compress4_table();
}  // namespace detail

// The lanes of `m` set, in order, moved to the lowest lanes (see vfloat16_avx512.h).
MLIB_INLINE vfloat4 compress(vfloat4 a, unsigned m) {
  const __m128i shuffle =
      _mm_loadu_si128(reinterpret_cast<const __m128i*>(detail::kCompress4[m & 0xFu].data()));
  return {_mm_castsi128_ps(_mm_shuffle_epi8(_mm_castps_si128(a.v), shuffle))};
}


// The smallest lane, in every lane (NaN lanes are not expected: callers select them away).
MLIB_INLINE vfloat4 reduce_min(vfloat4 a) {
  const __m128 m = _mm_min_ps(a.v, _mm_shuffle_ps(a.v, a.v, _MM_SHUFFLE(2, 3, 0, 1)));
  return {_mm_min_ps(m, _mm_shuffle_ps(m, m, _MM_SHUFFLE(1, 0, 3, 2)))};
}
// The largest lane, in every lane (likewise).
MLIB_INLINE vfloat4 reduce_max(vfloat4 a) {
  const __m128 m = _mm_max_ps(a.v, _mm_shuffle_ps(a.v, a.v, _MM_SHUFFLE(2, 3, 0, 1)));
  return {_mm_max_ps(m, _mm_shuffle_ps(m, m, _MM_SHUFFLE(1, 0, 3, 2)))};
}

}  // namespace mlib
