// mlib/vec4_functions.h — the free functions of vec4: dot, cross, normalize, clamp, abs,
// sqrt, min, max, calc_distance, to_color, str.
//
// Each takes vec4s or expressions alike and, where its result is a vector or a dot
// product, returns an expression node (nothing is computed until assignment). Edge
// semantics are listed in mlib/vec4.h.
#pragma once

#include <cstdint>
#include <string>

#include "mlib/vec4.h"

namespace mlib {

// Four-lane dot product (dpps). A scalar expression: converts to float, or acts as its
// value broadcast to four lanes inside vector arithmetic.
template <Expr A, Expr B>
MLIB_INLINE auto dot(const A& a, const B& b) {
  return make_binary<ops::Dot>(a, b);
}

// 3D cross product of lanes x y z; w of the result is 0 for finite inputs.
template <Expr A, Expr B>
MLIB_INLINE auto cross(const A& a, const B& b) {
  return make_binary<ops::Cross>(a, b);
}

template <Expr A>
MLIB_INLINE auto normalize(const A& a) {
  return make_unary<ops::Normalize>(a);
}

template <Expr A>
MLIB_INLINE auto abs(const A& a) {
  return make_unary<ops::Abs>(a);
}

template <Expr A>
MLIB_INLINE auto sqrt(const A& a) {
  return make_unary<ops::Sqrt>(a);
}

// Lane-wise min / max; a NaN in either operand's lane gives b's lane.
template <class A, class B>
  requires ExprOperands<A, B>
MLIB_INLINE auto min(const A& a, const B& b) {
  return make_binary<ops::Min>(a, b);
}
template <class A, class B>
  requires ExprOperands<A, B>
MLIB_INLINE auto max(const A& a, const B& b) {
  return make_binary<ops::Max>(a, b);
}

// Every lane into [lo, hi] (lo, hi may be floats or expressions); NaN lanes become lo.
template <Expr A, class Lo, class Hi>
  requires(Expr<Lo> || Arithmetic<Lo>) && (Expr<Hi> || Arithmetic<Hi>)
MLIB_INLINE auto clamp(const A& a, const Lo& lo, const Hi& hi) {
  return min(max(a, lo), hi);
}

// Euclidean distance sqrt(dot(a - b, a - b)) (over four lanes; w is 0 for points).
template <Expr A, Expr B>
MLIB_INLINE float calc_distance(const A& a, const B& b) {
  const auto d = a - b;
  return simd::lane0(simd::sqrt(ops::Dot::apply(d.eval(), d.eval())));
}

// RGB in [0, 1] (lanes x y z) to a packed 8-bit colour 0x00RRGGBB, rounded to nearest.
// Lanes are clamped to [0, 1] first; NaN gives 0.
template <Expr A>
MLIB_INLINE std::uint32_t to_color(const A& a) {
  const simd::f4 c = simd::min(simd::max(a.eval(), simd::zero()), simd::set1(1.0f));
  return simd::pack_rgb8(simd::mul(c, simd::set1(255.0f)));
}

// Each lane truncated toward zero and clamped to [lo, hi], into out[0..3] (NaN, and values
// beyond int32, give lo).
template <Expr A>
MLIB_INLINE void truncate_clamp(const A& a, std::int32_t lo, std::int32_t hi, std::int32_t* out) {
  simd::truncate_clamp(a.eval(), lo, hi, out);
}

// Four dot products in one go: (a0·b0, a1·b1, a2·b2, a3·b3), each over all four lanes.
// Cheaper than four dpps where dpps is slow; the rounding may differ from dot() in the
// last bit (different summation order).
template <Expr A0, Expr B0, Expr A1, Expr B1, Expr A2, Expr B2, Expr A3, Expr B3>
MLIB_INLINE vec4 dot4(const A0& a0, const B0& b0, const A1& a1, const B1& b1, const A2& a2,
                      const B2& b2, const A3& a3, const B3& b3) {
  return vec4(simd::dot4(a0.eval(), b0.eval(), a1.eval(), b1.eval(), a2.eval(), b2.eval(),
                         a3.eval(), b3.eval()));
}

// Minimum / maximum of lanes x, y, z.
template <Expr A>
MLIB_INLINE float hmin3(const A& a) {
  return simd::hmin3(a.eval());
}
template <Expr A>
MLIB_INLINE float hmax3(const A& a) {
  return simd::hmax3(a.eval());
}

// Loads p[0], p[1], p[2] with w = 0; p[3] is read but its bits are discarded (a struct may
// keep an integer there).
MLIB_INLINE vec4 load_xyz(const float* p) { return vec4(simd::load_xyz0(p)); }

// "(x, y, z, w)" with enough digits to read the floats back exactly.
std::string str(const vec4& v);
template <Expr A>
std::string str(const A& a) {
  return str(vec4(a));
}

}  // namespace mlib
