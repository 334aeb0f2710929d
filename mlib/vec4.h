// mlib/vec4.h — four floats in one 16-byte-aligned SIMD register (an __m128; a plain
// float[4] in the scalar build), the value type of rt2's math.
//
// vec4 is a leaf of the expression templates (mlib/expr.h): arithmetic on vec4s builds an
// expression tree, and assigning the tree to a vec4 evaluates it once. Every constructor
// and compound operator accepts an expression as well as a vec4 or a float. The free
// functions (dot, cross, normalize, clamp, abs, ...) are in mlib/vec4_functions.h.
#pragma once

#include <cstddef>

#include "mlib/expr.h"

namespace mlib {

// Conventions and edge semantics (tested in tests/mlib/):
// * Lanes are x y z w. rt2 stores 3D points and directions with w = 0, so the four-lane
//   dot product of the thesis (dpps) is the 3D one; the 3-argument constructor sets w = 0.
// * Arithmetic is IEEE single precision, lane by lane, rounded the same whatever the
//   expression's shape (the build disables FMA contraction).
// * dot of large vectors overflows to +inf once a lane's product or the sum exceeds
//   FLT_MAX (components around 1.8e19); products below FLT_MIN lose precision as
//   denormals and vanish below 1.4e-45. dot propagates NaN; inf * 0 gives NaN.
// * normalize is accurate to a few ulp for every finite nonzero vector, 1e-40 and 1e38
//   included (out-of-range lengths take a rescaling slow path). normalize of a zero vector
//   returns it unchanged (not NaN); a NaN or infinite lane gives NaN in every lane.
// * Comparisons (== != < <= > >=) are true when the relation holds in ALL four lanes, with
//   ordered IEEE semantics: any NaN lane makes them false, except != which is !(==).
//   +0 == -0. They are not a strict weak order: do not sort vec4s with them.
// * clamp maps NaN lanes to the lower bound; to_color maps NaN to 0.
class alignas(16) vec4 {
 public:
  using expr_tag = void;  // a leaf of the expression templates
  static constexpr bool scalar = false;

  MLIB_INLINE vec4() : m_(simd::zero()) {}
  MLIB_INLINE vec4(float x, float y, float z, float w) : m_(simd::setr(x, y, z, w)) {}
  MLIB_INLINE vec4(float x, float y, float z) : m_(simd::setr(x, y, z, 0.0f)) {}
  MLIB_INLINE explicit vec4(float s) : m_(simd::set1(s)) {}
  MLIB_INLINE vec4(simd::f4 m) : m_(m) {}  // NOLINT: implicit, as the thesis's vec4
  // Loads four floats; the pointer need not be 16-byte aligned.
  MLIB_INLINE explicit vec4(const float* p) : m_(simd::load(p)) {}
  template <Expr E>
  MLIB_INLINE vec4(const E& e) : m_(e.eval()) {}  // NOLINT: evaluating is the point

  MLIB_INLINE vec4(const vec4&) = default;
  MLIB_INLINE vec4& operator=(const vec4&) = default;
  template <Expr E>
  MLIB_INLINE vec4& operator=(const E& e) {
    m_ = e.eval();
    return *this;
  }

  MLIB_INLINE simd::f4 eval() const { return m_; }
  MLIB_INLINE simd::f4 m128() const { return m_; }

  MLIB_INLINE void set(float x, float y, float z, float w) { m_ = simd::setr(x, y, z, w); }
  MLIB_INLINE static vec4 zero() { return vec4(); }
  MLIB_INLINE void store(float* p) const { simd::store(p, m_); }

  // In place: see ops::Normalize (zero stays zero; NaN / inf give NaN).
  MLIB_INLINE void normalize() { m_ = ops::Normalize::apply(m_); }
  // In place: every lane into [lo, hi]; NaN lanes become lo.
  MLIB_INLINE void clamp(float lo, float hi) {
    m_ = simd::min(simd::max(m_, simd::set1(lo)), simd::set1(hi));
  }

  template <class E>
    requires Expr<E> || Arithmetic<E>
  MLIB_INLINE vec4& operator+=(const E& e) {
    m_ = simd::add(m_, detail::as_expr(e).eval());
    return *this;
  }
  template <class E>
    requires Expr<E> || Arithmetic<E>
  MLIB_INLINE vec4& operator-=(const E& e) {
    m_ = simd::sub(m_, detail::as_expr(e).eval());
    return *this;
  }
  template <class E>
    requires Expr<E> || Arithmetic<E>
  MLIB_INLINE vec4& operator*=(const E& e) {
    m_ = simd::mul(m_, detail::as_expr(e).eval());
    return *this;
  }
  template <class E>
    requires Expr<E> || Arithmetic<E>
  MLIB_INLINE vec4& operator/=(const E& e) {
    m_ = simd::div(m_, detail::as_expr(e).eval());
    return *this;
  }

  // Lane access (i in 0..3, unchecked). Well defined: __m128 may alias float, and the scalar
  // build's f4 begins with float[4].
  MLIB_INLINE float operator[](std::size_t i) const {
    return reinterpret_cast<const float*>(&m_)[i];
  }
  MLIB_INLINE float& operator[](std::size_t i) { return reinterpret_cast<float*>(&m_)[i]; }
  MLIB_INLINE float x() const { return simd::lane0(m_); }
  MLIB_INLINE float y() const { return simd::lane0(simd::shuffle<1, 1, 1, 1>(m_)); }
  MLIB_INLINE float z() const { return simd::lane0(simd::shuffle<2, 2, 2, 2>(m_)); }
  MLIB_INLINE float w() const { return simd::lane0(simd::shuffle<3, 3, 3, 3>(m_)); }

 private:
  simd::f4 m_;
};

static_assert(sizeof(vec4) == 16 && alignof(vec4) == 16, "vec4 is exactly four floats");

}  // namespace mlib
