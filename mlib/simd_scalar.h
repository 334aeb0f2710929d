// mlib/simd_scalar.h — mlib's four-float type without SIMD: plain C++, lane by lane.
//
// The same API as the SSE wrappers in mlib/simd.h (names, signatures and documented
// semantics), selected there when MLIB_SCALAR is defined (scons arch=scalar). It is the
// "no SIMD" rung of the thesis's speed-up ladder, so it must be honest scalar code: no
// intrinsics, no vector types, no <immintrin.h>; the build also forbids the compiler to
// vectorise (-fno-tree-vectorize -fno-tree-slp-vectorize). Both builds compute the same
// bits wherever IEEE fixes them (see below).
//
// Include mlib/simd.h, not this file: it defines MLIB_INLINE and makes the choice.
#pragma once

#if !defined(MLIB_INLINE)
#error "include mlib/simd.h, which selects this file when MLIB_SCALAR is defined"
#endif

#include <bit>
#include <cmath>
#include <cstdint>

namespace mlib::simd {

// Each function computes the bits of the SSE instruction it mirrors wherever IEEE fixes
// them: the same operand order and summation order, and the same NaN and signed-zero rules:
//   min(a, b) / max(a, b) return b in a lane where either operand is NaN (minps / maxps),
//   and b for min(+0, -0) too, because the test is a strict `a < b`;
//   comparisons return lane masks of all-one or all-zero bits (cmpps), so masks can be
//   combined with bit_and / bit_andnot and consumed by blend / movemask unchanged;
//   dp_* sums as dpps does: (x*x' + y*y') + (z*z' + w*w').
// Bit operations go through std::bit_cast, never through a float, so NaN payloads and the
// all-ones mask pattern survive. Which NaN comes out of arithmetic on two NaNs is left open
// by IEEE and may differ from the SSE build (x86 returns the first operand's, and the
// compiler may commute a * b); where the result is NaN is the same.

// 16-byte aligned like __m128, so vec4 keeps its size, alignment and layout in both builds.
struct alignas(16) f4 {
  float v[4];
};

namespace detail {

MLIB_INLINE std::uint32_t bits(float f) { return std::bit_cast<std::uint32_t>(f); }
MLIB_INLINE float from_bits(std::uint32_t u) { return std::bit_cast<float>(u); }
// What cmpps writes into a lane: every bit set (a NaN pattern) or every bit clear.
MLIB_INLINE float mask_lane(bool b) { return from_bits(b ? 0xFFFFFFFFu : 0u); }
MLIB_INLINE bool sign_bit(float f) { return (bits(f) >> 31) != 0; }

}  // namespace detail

// --- construction and memory ---------------------------------------------------------
MLIB_INLINE f4 zero() { return f4{{0.0f, 0.0f, 0.0f, 0.0f}}; }
MLIB_INLINE f4 set1(float s) { return f4{{s, s, s, s}}; }
MLIB_INLINE f4 setr(float x, float y, float z, float w) { return f4{{x, y, z, w}}; }
MLIB_INLINE f4 load(const float* p) {  // any alignment, like _mm_loadu_ps
  f4 r;
  for (int i = 0; i < 4; ++i) r.v[i] = p[i];
  return r;
}
MLIB_INLINE void store(float* p, f4 a) {
  for (int i = 0; i < 4; ++i) p[i] = a.v[i];
}
// Loads p[0..2] and sets lane w to 0. The SSE version reads p[3] and discards it; here it
// is not read at all, which the same contract (p[3] readable, any bits) allows.
MLIB_INLINE f4 load_xyz0(const float* p) { return f4{{p[0], p[1], p[2], 0.0f}}; }
MLIB_INLINE float lane0(f4 a) { return a.v[0]; }

// --- lane-wise arithmetic ------------------------------------------------------------
MLIB_INLINE f4 add(f4 a, f4 b) {
  f4 r;
  for (int i = 0; i < 4; ++i) r.v[i] = a.v[i] + b.v[i];
  return r;
}
MLIB_INLINE f4 sub(f4 a, f4 b) {
  f4 r;
  for (int i = 0; i < 4; ++i) r.v[i] = a.v[i] - b.v[i];
  return r;
}
MLIB_INLINE f4 mul(f4 a, f4 b) {
  f4 r;
  for (int i = 0; i < 4; ++i) r.v[i] = a.v[i] * b.v[i];
  return r;
}
MLIB_INLINE f4 div(f4 a, f4 b) {
  f4 r;
  for (int i = 0; i < 4; ++i) r.v[i] = a.v[i] / b.v[i];
  return r;
}
// minps / maxps are exactly `a < b ? a : b` / `a > b ? a : b`: a NaN in either lane makes
// the test false and gives b. (std::fmin / std::fmax would return the non-NaN operand.)
MLIB_INLINE f4 min(f4 a, f4 b) {
  f4 r;
  for (int i = 0; i < 4; ++i) r.v[i] = a.v[i] < b.v[i] ? a.v[i] : b.v[i];
  return r;
}
MLIB_INLINE f4 max(f4 a, f4 b) {
  f4 r;
  for (int i = 0; i < 4; ++i) r.v[i] = a.v[i] > b.v[i] ? a.v[i] : b.v[i];
  return r;
}
// IEEE square root, correctly rounded like sqrtps. With the build's -fno-math-errno this is
// one sqrtss per lane; without it, negative lanes also take libm's errno path (still NaN).
MLIB_INLINE f4 sqrt(f4 a) {
  f4 r;
  for (int i = 0; i < 4; ++i) r.v[i] = std::sqrt(a.v[i]);
  return r;
}
// Sign-bit flips and clears, as the SSE xor / andnot with -0.0f: exact for NaN and ±0.
MLIB_INLINE f4 neg(f4 a) {
  f4 r;
  for (int i = 0; i < 4; ++i) r.v[i] = detail::from_bits(detail::bits(a.v[i]) ^ 0x80000000u);
  return r;
}
MLIB_INLINE f4 abs(f4 a) {
  f4 r;
  for (int i = 0; i < 4; ++i) r.v[i] = detail::from_bits(detail::bits(a.v[i]) & 0x7FFFFFFFu);
  return r;
}

// --- bitwise -------------------------------------------------------------------------
MLIB_INLINE f4 bit_and(f4 a, f4 b) {
  f4 r;
  for (int i = 0; i < 4; ++i)
    r.v[i] = detail::from_bits(detail::bits(a.v[i]) & detail::bits(b.v[i]));
  return r;
}
MLIB_INLINE f4 bit_or(f4 a, f4 b) {
  f4 r;
  for (int i = 0; i < 4; ++i)
    r.v[i] = detail::from_bits(detail::bits(a.v[i]) | detail::bits(b.v[i]));
  return r;
}
MLIB_INLINE f4 bit_andnot(f4 a, f4 b) {  // ~a & b
  f4 r;
  for (int i = 0; i < 4; ++i)
    r.v[i] = detail::from_bits(~detail::bits(a.v[i]) & detail::bits(b.v[i]));
  return r;
}
// blendvps looks only at the sign bit of each mask lane; so does this.
MLIB_INLINE f4 blend(f4 mask, f4 if_false, f4 if_true) {
  f4 r;
  for (int i = 0; i < 4; ++i)
    r.v[i] = detail::sign_bit(mask.v[i]) ? if_true.v[i] : if_false.v[i];
  return r;
}

// --- dot products (the dpps summation order) -----------------------------------------
// All four lanes are multiplied and summed as (x + y) + (z + w), each step rounded to
// float, which is what dpps does. `dp_lane0` (mask 0xF1) leaves +0 in lanes y z w;
// `dp_bcast` (mask 0xFF) puts the sum in every lane.
namespace detail {
MLIB_INLINE float dp_sum(f4 a, f4 b) {
  const float xy = a.v[0] * b.v[0] + a.v[1] * b.v[1];
  const float zw = a.v[2] * b.v[2] + a.v[3] * b.v[3];
  return xy + zw;
}
}  // namespace detail
MLIB_INLINE f4 dp_bcast(f4 a, f4 b) { return set1(detail::dp_sum(a, b)); }
MLIB_INLINE f4 dp_lane0(f4 a, f4 b) { return f4{{detail::dp_sum(a, b), 0.0f, 0.0f, 0.0f}}; }

// --- shuffles ------------------------------------------------------------------------
template <int X, int Y, int Z, int W>
MLIB_INLINE f4 shuffle(f4 a) {
  static_assert(X >= 0 && X < 4 && Y >= 0 && Y < 4 && Z >= 0 && Z < 4 && W >= 0 && W < 4,
                "shuffle lanes are 0..3");
  return f4{{a.v[X], a.v[Y], a.v[Z], a.v[W]}};
}

// Four dot products at once: lane i of the result is a_i · b_i (all four lanes summed), in
// the SSE version's order (x + y) + (z + w), so it equals dp_bcast lane for lane here.
MLIB_INLINE f4 dot4(f4 a0, f4 b0, f4 a1, f4 b1, f4 a2, f4 b2, f4 a3, f4 b3) {
  return f4{{detail::dp_sum(a0, b0), detail::dp_sum(a1, b1), detail::dp_sum(a2, b2),
             detail::dp_sum(a3, b3)}};
}

// Four vectors' lanes regrouped (a 4x4 transpose): x = (a.x, b.x, c.x, d.x), y, z, w alike.
MLIB_INLINE void transpose4(f4 a, f4 b, f4 c, f4 d, f4& x, f4& y, f4& z, f4& w) {
  x = f4{{a.v[0], b.v[0], c.v[0], d.v[0]}};
  y = f4{{a.v[1], b.v[1], c.v[1], d.v[1]}};
  z = f4{{a.v[2], b.v[2], c.v[2], d.v[2]}};
  w = f4{{a.v[3], b.v[3], c.v[3], d.v[3]}};
}

// Horizontal minimum / maximum of lanes x, y, z (w ignored), as a float, in the order of
// the SSE version (min(min(x, y), z) with minss's rule): a NaN operand lets the second
// operand win, so `hmin3` of (NaN, 2, 3) may be 2 or NaN; callers that care clamp first.
MLIB_INLINE float hmin3(f4 a) {
  const float m = a.v[0] < a.v[1] ? a.v[0] : a.v[1];
  return m < a.v[2] ? m : a.v[2];
}
MLIB_INLINE float hmax3(f4 a) {
  const float m = a.v[0] > a.v[1] ? a.v[0] : a.v[1];
  return m > a.v[2] ? m : a.v[2];
}

// (a.yzx * b.zxy - a.zxy * b.yzx), with each lane's products in the SSE version's operand
// order; lane w is a.w*b.w - a.w*b.w = 0 for finite w (NaN for infinite or NaN w, as there).
MLIB_INLINE f4 cross(f4 a, f4 b) {
  return f4{{a.v[1] * b.v[2] - a.v[2] * b.v[1], a.v[2] * b.v[0] - a.v[0] * b.v[2],
             a.v[0] * b.v[1] - a.v[1] * b.v[0], a.v[3] * b.v[3] - a.v[3] * b.v[3]}};
}

// --- comparisons: lane masks and their reduction -------------------------------------
// C++'s ordered float comparisons are false on NaN and != is true, exactly the cmpps
// predicates used by the SSE version (EQ_OQ, LT_OS, LE_OS, NEQ_UQ; gt / ge swap operands).
MLIB_INLINE f4 cmp_eq(f4 a, f4 b) {
  f4 r;
  for (int i = 0; i < 4; ++i) r.v[i] = detail::mask_lane(a.v[i] == b.v[i]);
  return r;
}
MLIB_INLINE f4 cmp_ne(f4 a, f4 b) {
  f4 r;
  for (int i = 0; i < 4; ++i) r.v[i] = detail::mask_lane(a.v[i] != b.v[i]);
  return r;
}
MLIB_INLINE f4 cmp_lt(f4 a, f4 b) {
  f4 r;
  for (int i = 0; i < 4; ++i) r.v[i] = detail::mask_lane(a.v[i] < b.v[i]);
  return r;
}
MLIB_INLINE f4 cmp_le(f4 a, f4 b) {
  f4 r;
  for (int i = 0; i < 4; ++i) r.v[i] = detail::mask_lane(a.v[i] <= b.v[i]);
  return r;
}
MLIB_INLINE f4 cmp_gt(f4 a, f4 b) {
  f4 r;
  for (int i = 0; i < 4; ++i) r.v[i] = detail::mask_lane(a.v[i] > b.v[i]);
  return r;
}
MLIB_INLINE f4 cmp_ge(f4 a, f4 b) {
  f4 r;
  for (int i = 0; i < 4; ++i) r.v[i] = detail::mask_lane(a.v[i] >= b.v[i]);
  return r;
}
// Sign bit of lane i into bit i, like movmskps (so any float, not only a mask, works).
MLIB_INLINE int movemask(f4 m) {
  int r = 0;
  for (int i = 0; i < 4; ++i) r |= int(detail::sign_bit(m.v[i])) << i;
  return r;
}
MLIB_INLINE bool all(f4 m) { return movemask(m) == 0xF; }
MLIB_INLINE bool any(f4 m) { return movemask(m) != 0; }

// --- conversion ----------------------------------------------------------------------
namespace detail {
// cvtps2dq on one lane: round in the current rounding mode (nearest-even by default, as
// MXCSR), and the "integer indefinite" 0x80000000 for NaN and values outside int32.
// std::lrint rather than std::nearbyint: with -fno-math-errno it is one scalar cvtss2si,
// not a libm call, and in the guarded range the two round identically.
MLIB_INLINE std::int32_t cvt_lane(float f) {
  if (!(f >= -2147483648.0f && f < 2147483648.0f)) return INT32_MIN;
  return static_cast<std::int32_t>(std::lrint(f));
}
}  // namespace detail
// Round to nearest (even), then pack lanes x y z as 0x00RRGGBB, with the same expression
// as the SSE version (no masking). Callers clamp to [0, 255] first.
MLIB_INLINE std::uint32_t pack_rgb8(f4 a) {
  const auto r = static_cast<std::uint32_t>(detail::cvt_lane(a.v[0]));
  const auto g = static_cast<std::uint32_t>(detail::cvt_lane(a.v[1]));
  const auto b = static_cast<std::uint32_t>(detail::cvt_lane(a.v[2]));
  return (r << 16) | (g << 8) | b;
}

// Truncate toward zero (NaN and values outside int32 give INT32_MIN, as cvttps2dq), clamp
// to [lo, hi] and store the four lanes.
MLIB_INLINE void truncate_clamp(f4 a, std::int32_t lo, std::int32_t hi, std::int32_t* out) {
  for (int k = 0; k < 4; ++k) {
    const float f = a.v[k];
    const std::int32_t i =
        f >= -2147483648.0f && f < 2147483648.0f ? static_cast<std::int32_t>(f) : INT32_MIN;
    out[k] = i < lo ? lo : (i > hi ? hi : i);
  }
}

MLIB_INLINE f4 zero_w(f4 a) { return f4{{a.v[0], a.v[1], a.v[2], 0.0f}}; }

// See simd.h: bits plus trunc(k), minus where a < 0, wrapping.
MLIB_INLINE f4 step_ulps(f4 a, f4 k) {
  f4 r;
  for (int i = 0; i < 4; ++i) {
    const float f = k.v[i];
    const std::int32_t steps =
        f >= -2147483648.0f && f < 2147483648.0f ? static_cast<std::int32_t>(f) : INT32_MIN;
    const auto u = static_cast<std::uint32_t>(steps);
    r.v[i] = std::bit_cast<float>(std::bit_cast<std::uint32_t>(a.v[i]) + (a.v[i] < 0.0f ? 0u - u : u));
  }
  return r;
}

}  // namespace mlib::simd
