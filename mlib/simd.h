// mlib/simd.h — the only file of mlib that touches SSE intrinsics.
//
// Thin, always-inlined wrappers over __m128 (four floats, lanes x y z w). Everything above
// this file (expression nodes, vec4) speaks in these names, so a wider instruction set later
// is a sibling file, not an #ifdef. SSE4.1 is the baseline: `dp` is `dpps`.
//
// NaN conventions of the underlying instructions, which callers rely on and document:
//   min(a, b) / max(a, b) return b in a lane where either operand is NaN (minps / maxps);
//   every ordered comparison (lt, le, gt, ge, eq) is false in a NaN lane; ne is true.
#pragma once

#include <cstdint>

#if defined(__GNUC__)
#define MLIB_INLINE inline __attribute__((always_inline))
#else
#define MLIB_INLINE inline
#endif

namespace mlib {
// Asks for the `lines` cache lines from p on (into every cache level), without waiting: a
// hint, never a fault, whatever p is.
MLIB_INLINE void prefetch(const void* p, int lines = 1) {
  for (int i = 0; i < lines; ++i) __builtin_prefetch(static_cast<const char*>(p) + 64 * i, 0, 3);
}
// The same for lines about to be written (owned, so that the stores do not wait for them).
MLIB_INLINE void prefetch_for_write(const void* p, int lines = 1) {
  for (int i = 0; i < lines; ++i) __builtin_prefetch(static_cast<const char*>(p) + 64 * i, 1, 3);
}
}  // namespace mlib

// MLIB_SCALAR (scons arch=scalar) swaps the whole file for the same API in plain lane-by-
// lane C++: the thesis's "no SIMD" baseline, measured against the SSE code below. Nothing
// above this layer changes, so the two builds differ only in how f4 is computed.
#if defined(MLIB_SCALAR)
#include "mlib/simd_scalar.h"
#else

#include <smmintrin.h>  // SSE4.1

namespace mlib::simd {

using f4 = __m128;

// --- construction and memory ---------------------------------------------------------
MLIB_INLINE f4 zero() { return _mm_setzero_ps(); }
MLIB_INLINE f4 set1(float s) { return _mm_set1_ps(s); }
MLIB_INLINE f4 setr(float x, float y, float z, float w) { return _mm_setr_ps(x, y, z, w); }
MLIB_INLINE f4 load(const float* p) { return _mm_loadu_ps(p); }
MLIB_INLINE void store(float* p, f4 a) { _mm_storeu_ps(p, a); }
// a with lane w set to +0.
MLIB_INLINE f4 zero_w(f4 a) { return _mm_blend_ps(a, _mm_setzero_ps(), 0x8); }
// Loads p[0..2] and sets lane w to 0 (p[3] is read but discarded: it may hold any bits).
MLIB_INLINE f4 load_xyz0(const float* p) { return zero_w(_mm_loadu_ps(p)); }
MLIB_INLINE float lane0(f4 a) { return _mm_cvtss_f32(a); }

// --- lane-wise arithmetic ------------------------------------------------------------
MLIB_INLINE f4 add(f4 a, f4 b) { return _mm_add_ps(a, b); }
MLIB_INLINE f4 sub(f4 a, f4 b) { return _mm_sub_ps(a, b); }
MLIB_INLINE f4 mul(f4 a, f4 b) { return _mm_mul_ps(a, b); }
MLIB_INLINE f4 div(f4 a, f4 b) { return _mm_div_ps(a, b); }
MLIB_INLINE f4 min(f4 a, f4 b) { return _mm_min_ps(a, b); }
MLIB_INLINE f4 max(f4 a, f4 b) { return _mm_max_ps(a, b); }
MLIB_INLINE f4 sqrt(f4 a) { return _mm_sqrt_ps(a); }
MLIB_INLINE f4 neg(f4 a) { return _mm_xor_ps(a, _mm_set1_ps(-0.0f)); }
MLIB_INLINE f4 abs(f4 a) { return _mm_andnot_ps(_mm_set1_ps(-0.0f), a); }

// --- bitwise -------------------------------------------------------------------------
MLIB_INLINE f4 bit_and(f4 a, f4 b) { return _mm_and_ps(a, b); }
MLIB_INLINE f4 bit_or(f4 a, f4 b) { return _mm_or_ps(a, b); }
MLIB_INLINE f4 bit_andnot(f4 a, f4 b) { return _mm_andnot_ps(a, b); }  // ~a & b
MLIB_INLINE f4 blend(f4 mask, f4 if_false, f4 if_true) {
  return _mm_blendv_ps(if_false, if_true, mask);
}

// --- dot products (SSE4.1 dpps) ------------------------------------------------------
// All four lanes are multiplied and summed as dpps does, (x x' + y y') + (z z' + w w'),
// each step rounded. `dp_lane0` is the thesis's form (mask 0xF1, result in lane 0);
// `dp_bcast` (mask 0xFF) puts the sum in every lane, which saves the shuffle when the
// result is used as a vector.
//
// In the translation units of the AVX2 and AVX-512 ray kernels (the build defines
// MLIB_SHUFFLED_DOT for them alone, rt2/base/isa.h), dp_bcast is one multiply and two
// shuffle-adds instead, every lane summing (x x' + y y') + (z z' + w w') with its operands
// in that order: the same bits, without dpps's four micro-ops and long latency, which slow
// the kernel's hit shading. The baseline keeps dpps, the thesis's form
// (tests/mlib/asm_test.cpp counts its instructions), also where it is built with AVX2
// (scons arch=native). Each form lives in an inline namespace of its own, so the two
// dp_bcast never share a symbol; their callers (vec4's dot, normalize, ...) are
// always-inline, so no out-of-line copy of one is ever shared either
// (tests/rt2/base/isa_test.cpp checks that no wide instruction leaves the wide units).
#if defined(MLIB_SHUFFLED_DOT)
inline namespace shuffled_dot {
MLIB_INLINE f4 dp_bcast(f4 a, f4 b) {
  const __m128 m = _mm_mul_ps(a, b);
  const __m128 pairs = _mm_add_ps(_mm_moveldup_ps(m), _mm_movehdup_ps(m));  // x+y, z+w
  return _mm_add_ps(_mm_movelh_ps(pairs, pairs), _mm_movehl_ps(pairs, pairs));
}
}  // namespace shuffled_dot
#else
inline namespace dpps_dot {
MLIB_INLINE f4 dp_bcast(f4 a, f4 b) { return _mm_dp_ps(a, b, 0xFF); }
}  // namespace dpps_dot
#endif
MLIB_INLINE f4 dp_lane0(f4 a, f4 b) { return _mm_dp_ps(a, b, 0xF1); }

// --- shuffles ------------------------------------------------------------------------
template <int X, int Y, int Z, int W>
MLIB_INLINE f4 shuffle(f4 a) {
  return _mm_shuffle_ps(a, a, _MM_SHUFFLE(W, Z, Y, X));
}

// Four dot products at once: lane i of the result is a_i · b_i (all four lanes summed).
// Four multiplies, a 4x4 transpose and three adds: on CPUs where dpps is slow this is
// much cheaper than four dpps. Sums lanes in the order (x + y) + (z + w).
MLIB_INLINE f4 dot4(f4 a0, f4 b0, f4 a1, f4 b1, f4 a2, f4 b2, f4 a3, f4 b3) {
  __m128 p0 = _mm_mul_ps(a0, b0), p1 = _mm_mul_ps(a1, b1);
  __m128 p2 = _mm_mul_ps(a2, b2), p3 = _mm_mul_ps(a3, b3);
  _MM_TRANSPOSE4_PS(p0, p1, p2, p3);  // p0 = x lanes, p1 = y lanes, ...
  return _mm_add_ps(_mm_add_ps(p0, p1), _mm_add_ps(p2, p3));
}

// Four vectors' lanes regrouped (a 4x4 transpose): x = (a.x, b.x, c.x, d.x), y, z, w alike.
// Structure of arrays from four vectors in four shuffles and four unpacks.
MLIB_INLINE void transpose4(f4 a, f4 b, f4 c, f4 d, f4& x, f4& y, f4& z, f4& w) {
  _MM_TRANSPOSE4_PS(a, b, c, d);
  x = a, y = b, z = c, w = d;
}

// Horizontal minimum / maximum of lanes x, y, z (w ignored), as a float. NaN lanes follow
// minss/maxss: the second operand wins, so `hmin3` of (NaN, 2, 3) may be 2 or NaN; callers
// that care clamp NaN away first.
MLIB_INLINE float hmin3(f4 a) {
  const f4 m = _mm_min_ss(a, shuffle<1, 1, 1, 1>(a));
  return _mm_cvtss_f32(_mm_min_ss(m, shuffle<2, 2, 2, 2>(a)));
}
MLIB_INLINE float hmax3(f4 a) {
  const f4 m = _mm_max_ss(a, shuffle<1, 1, 1, 1>(a));
  return _mm_cvtss_f32(_mm_max_ss(m, shuffle<2, 2, 2, 2>(a)));
}

// (a.yzx * b.zxy - a.zxy * b.yzx); lane w is a.w*b.w - a.w*b.w = 0 for finite w.
MLIB_INLINE f4 cross(f4 a, f4 b) {
  const f4 a_yzx = shuffle<1, 2, 0, 3>(a);
  const f4 b_yzx = shuffle<1, 2, 0, 3>(b);
  const f4 c = _mm_sub_ps(_mm_mul_ps(a, b_yzx), _mm_mul_ps(a_yzx, b));
  return shuffle<1, 2, 0, 3>(c);
}

// --- comparisons: lane masks and their reduction -------------------------------------
MLIB_INLINE f4 cmp_eq(f4 a, f4 b) { return _mm_cmpeq_ps(a, b); }
MLIB_INLINE f4 cmp_ne(f4 a, f4 b) { return _mm_cmpneq_ps(a, b); }
MLIB_INLINE f4 cmp_lt(f4 a, f4 b) { return _mm_cmplt_ps(a, b); }
MLIB_INLINE f4 cmp_le(f4 a, f4 b) { return _mm_cmple_ps(a, b); }
MLIB_INLINE f4 cmp_gt(f4 a, f4 b) { return _mm_cmpgt_ps(a, b); }
MLIB_INLINE f4 cmp_ge(f4 a, f4 b) { return _mm_cmpge_ps(a, b); }
MLIB_INLINE int movemask(f4 m) { return _mm_movemask_ps(m); }
MLIB_INLINE bool all(f4 m) { return _mm_movemask_ps(m) == 0xF; }
MLIB_INLINE bool any(f4 m) { return _mm_movemask_ps(m) != 0; }

// --- conversion ----------------------------------------------------------------------
// Round to nearest (even) under the default MXCSR, then pack the low byte of lanes x y z
// as 0x00RRGGBB. Callers clamp to [0, 255] first.
MLIB_INLINE std::uint32_t pack_rgb8(f4 a) {
  const __m128i i = _mm_cvtps_epi32(a);
  const auto r = static_cast<std::uint32_t>(_mm_extract_epi32(i, 0));
  const auto g = static_cast<std::uint32_t>(_mm_extract_epi32(i, 1));
  const auto b = static_cast<std::uint32_t>(_mm_extract_epi32(i, 2));
  return (r << 16) | (g << 8) | b;
}

// Truncate toward zero (NaN and values outside int32 give INT32_MIN), clamp to [lo, hi]
// and store the four lanes.
MLIB_INLINE void truncate_clamp(f4 a, std::int32_t lo, std::int32_t hi, std::int32_t* out) {
  const __m128i i = _mm_cvttps_epi32(a);
  _mm_storeu_si128(reinterpret_cast<__m128i*>(out),
                   _mm_min_epi32(_mm_max_epi32(i, _mm_set1_epi32(lo)), _mm_set1_epi32(hi)));
}

// Each lane's bits, read as an int32, plus k truncated toward zero (NaN and values outside
// int32 give INT32_MIN), or minus it where a < 0, wrapping: a moved by trunc(k) floats,
// away from zero for k > 0 (Wächter and Binder's offset, rt2/geometry/offset.h).
MLIB_INLINE f4 step_ulps(f4 a, f4 k) {
  const __m128i steps = _mm_cvttps_epi32(k);
  const __m128i negative = _mm_castps_si128(_mm_cmplt_ps(a, _mm_setzero_ps()));
  const __m128i signed_steps = _mm_sub_epi32(_mm_xor_si128(steps, negative), negative);
  return _mm_castsi128_ps(_mm_add_epi32(_mm_castps_si128(a), signed_steps));
}

}  // namespace mlib::simd

#endif  // MLIB_SCALAR
