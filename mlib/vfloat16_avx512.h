// mlib/vfloat16_avx512.h — vfloat16 / vbool16: sixteen independent float lanes on AVX-512
// (a mask register for the booleans), the sibling of vfloat4_sse41.h and vfloat8_avx2.h
// with the same API (see there). Included only by the translation units built for AVX-512
// (rt2/base/isa.h); the packet code takes a packet's 16 rays in one pass with it.
#pragma once

#include <immintrin.h>

#include <cstdint>

#include "mlib/simd.h"  // MLIB_INLINE

#if !defined(__AVX512F__)
#error "mlib/vfloat16_avx512.h needs AVX-512: include it only from a translation unit built for it"
#endif

namespace mlib {

struct vbool16 {
  __mmask16 m;
  static constexpr int size = 16;
  // Lane i set where bit i of `b` is.
  MLIB_INLINE static vbool16 from_bits(unsigned b) { return {static_cast<__mmask16>(b)}; }
};

struct vfloat16 {
  __m512 v;
  static constexpr int size = 16;
  using bool_type = vbool16;

  MLIB_INLINE static vfloat16 broadcast(float s) { return {_mm512_set1_ps(s)}; }
  MLIB_INLINE static vfloat16 load(const float* p) { return {_mm512_load_ps(p)}; }  // 64-byte aligned
  MLIB_INLINE void store(float* p) const { _mm512_store_ps(p, v); }
  MLIB_INLINE static vfloat16 loadu(const void* p) { return {_mm512_loadu_ps(p)}; }  // any alignment
  // Lane i = p[i] as a float (16 bytes, any alignment).
  MLIB_INLINE static vfloat16 from_bytes(const std::uint8_t* p) {
    return {_mm512_cvtepi32_ps(_mm512_cvtepu8_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p))))};
  }
  // p[0 ... 3] in every four lanes.
  MLIB_INLINE static vfloat16 broadcast_quad(const float* p) {
    return {_mm512_broadcast_f32x4(_mm_loadu_ps(p))};
  }
  // Lane i = src[ids[i / 4]]: four rays' values (of 16, src) each over four lanes.
  MLIB_INLINE static vfloat16 spread_quads(const float* src, const std::uint32_t* ids) {
    const __m512i quad = _mm512_setr_epi32(0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3);
    const __m512i idx = _mm512_permutexvar_epi32(
        quad, _mm512_castsi128_si512(_mm_loadu_si128(reinterpret_cast<const __m128i*>(ids))));
    return {_mm512_permutexvar_ps(idx, _mm512_loadu_ps(src))};
  }
  MLIB_INLINE void storeu(void* p) const { _mm512_storeu_ps(p, v); }
};

MLIB_INLINE vfloat16 operator+(vfloat16 a, vfloat16 b) { return {_mm512_add_ps(a.v, b.v)}; }
MLIB_INLINE vfloat16 operator-(vfloat16 a, vfloat16 b) { return {_mm512_sub_ps(a.v, b.v)}; }
MLIB_INLINE vfloat16 operator*(vfloat16 a, vfloat16 b) { return {_mm512_mul_ps(a.v, b.v)}; }
MLIB_INLINE vfloat16 operator/(vfloat16 a, vfloat16 b) { return {_mm512_div_ps(a.v, b.v)}; }
// a * b + c, rounded once.
MLIB_INLINE vfloat16 fmadd(vfloat16 a, vfloat16 b, vfloat16 c) { return {_mm512_fmadd_ps(a.v, b.v, c.v)}; }
// The SSE rule: when a lane is NaN, the second operand's lane.
MLIB_INLINE vfloat16 min(vfloat16 a, vfloat16 b) { return {_mm512_min_ps(a.v, b.v)}; }
MLIB_INLINE vfloat16 max(vfloat16 a, vfloat16 b) { return {_mm512_max_ps(a.v, b.v)}; }
MLIB_INLINE vfloat16 abs(vfloat16 a) {
  return {_mm512_castsi512_ps(_mm512_andnot_si512(_mm512_set1_epi32(int(0x80000000u)),
                                                  _mm512_castps_si512(a.v)))};
}
MLIB_INLINE vfloat16 sqrt(vfloat16 a) { return {_mm512_sqrt_ps(a.v)}; }  // correctly rounded
MLIB_INLINE vfloat16 floor(vfloat16 a) {
  return {_mm512_roundscale_ps(a.v, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC)};
}
MLIB_INLINE vfloat16 step_ulps(vfloat16 a, vfloat16 k) {  // see mlib/simd.h
  const __m512i steps = _mm512_cvttps_epi32(k.v);
  const __mmask16 negative = _mm512_cmp_ps_mask(a.v, _mm512_setzero_ps(), _CMP_LT_OQ);
  return {_mm512_castsi512_ps(_mm512_mask_sub_epi32(
      _mm512_add_epi32(_mm512_castps_si512(a.v), steps), negative, _mm512_castps_si512(a.v), steps))};
}
MLIB_INLINE vfloat16 xor_sign(vfloat16 a, vfloat16 s) {
  const __m512i sign = _mm512_and_si512(_mm512_castps_si512(s.v), _mm512_set1_epi32(int(0x80000000u)));
  return {_mm512_castsi512_ps(_mm512_xor_si512(_mm512_castps_si512(a.v), sign))};
}

MLIB_INLINE vbool16 operator<(vfloat16 a, vfloat16 b) { return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_LT_OQ)}; }
MLIB_INLINE vbool16 operator<=(vfloat16 a, vfloat16 b) { return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_LE_OQ)}; }
MLIB_INLINE vbool16 operator>(vfloat16 a, vfloat16 b) { return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_GT_OQ)}; }
MLIB_INLINE vbool16 operator>=(vfloat16 a, vfloat16 b) { return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_GE_OQ)}; }
MLIB_INLINE vbool16 operator==(vfloat16 a, vfloat16 b) { return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_EQ_OQ)}; }
MLIB_INLINE vbool16 operator!=(vfloat16 a, vfloat16 b) { return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_NEQ_UQ)}; }  // true for NaN
MLIB_INLINE vbool16 operator&(vbool16 a, vbool16 b) { return {static_cast<__mmask16>(a.m & b.m)}; }
MLIB_INLINE vbool16 operator|(vbool16 a, vbool16 b) { return {static_cast<__mmask16>(a.m | b.m)}; }
MLIB_INLINE vbool16 andnot(vbool16 a, vbool16 b) { return {static_cast<__mmask16>(~a.m & b.m)}; }  // ~a & b

// See vfloat4_sse41.h.
MLIB_INLINE vfloat16 imin(vfloat16 a, vfloat16 b) {
  return {_mm512_castsi512_ps(_mm512_min_epi32(_mm512_castps_si512(a.v), _mm512_castps_si512(b.v)))};
}
MLIB_INLINE vfloat16 imax(vfloat16 a, vfloat16 b) {
  return {_mm512_castsi512_ps(_mm512_max_epi32(_mm512_castps_si512(a.v), _mm512_castps_si512(b.v)))};
}
MLIB_INLINE vbool16 ile(vfloat16 a, vfloat16 b) {
  return {_mm512_cmple_epi32_mask(_mm512_castps_si512(a.v), _mm512_castps_si512(b.v))};
}

MLIB_INLINE vfloat16 select(vbool16 m, vfloat16 if_true, vfloat16 if_false) {
  return {_mm512_mask_blend_ps(m.m, if_false.v, if_true.v)};
}
MLIB_INLINE unsigned bits(vbool16 m) { return static_cast<unsigned>(m.m); }

// The lanes of `m` set, in order, moved to the lowest lanes (the lanes above them hold
// anything). Bits are moved, not computed: NaN payloads and signed zeros pass as they are.
// The same in every vfloat file.
MLIB_INLINE vfloat16 compress(vfloat16 a, unsigned m) {
  return {_mm512_maskz_compress_ps(static_cast<__mmask16>(m), a.v)};
}


// The smallest / largest lane, in every lane (as the SSE versions, NaN lanes not expected).
MLIB_INLINE vfloat16 reduce_min(vfloat16 a) { return {_mm512_set1_ps(_mm512_reduce_min_ps(a.v))}; }
MLIB_INLINE vfloat16 reduce_max(vfloat16 a) { return {_mm512_set1_ps(_mm512_reduce_max_ps(a.v))}; }

}  // namespace mlib
