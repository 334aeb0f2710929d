// mlib/expr.h — expression-template nodes over four-float SIMD values.
//
// `a + b * dot(c, d) - 0.5f * e` computes nothing when written: it builds a tree of the
// node types below, operands held by value (a leaf is 16 bytes, so the copy is a register
// move after inlining and an expression can never dangle). The tree is evaluated once,
// lane-parallel, by `eval()` when assigned to a vec4 or converted to float; with every
// `eval` forced inline, what is left is the bare SSE instruction sequence: no temporaries
// in memory and no calls. Three layers are kept apart: the intrinsics (mlib/simd.h), the
// operations (mlib/ops.h) and the node shapes here (one generic unary, one binary node).
#pragma once

#include <type_traits>

#include "mlib/ops.h"

namespace mlib {

// A node is *scalar* when all four lanes are known to hold the same value (a dot product,
// a float operand, lane-wise arithmetic of those). A scalar node converts implicitly to
// float (`float d = dot(a, b);`), and in vector arithmetic it is used as the broadcast
// value, so `n * dot(n, i)` needs no shuffle.

// Every expression node, and vec4 itself, declares `using expr_tag = void;`. (A member
// tag rather than a common base class: two subobjects of one empty base could not share an
// address, and every node would grow by padding.)
template <class E>
concept Expr = requires { typename std::remove_cvref_t<E>::expr_tag; };

template <class S>
concept Arithmetic = std::is_arithmetic_v<std::remove_cvref_t<S>>;

// A float operand, broadcast to four lanes.
struct ScalarLeaf {
  using expr_tag = void;
  static constexpr bool scalar = true;
  simd::f4 value;
  MLIB_INLINE explicit ScalarLeaf(float s) : value(simd::set1(s)) {}
  MLIB_INLINE simd::f4 eval() const { return value; }
  MLIB_INLINE operator float() const { return simd::lane0(value); }
};

template <class Op, class A>
struct Unary {
  using expr_tag = void;
  static constexpr bool scalar = Op::kind == ops::Kind::reduction ||
                                 (Op::kind == ops::Kind::lanewise && A::scalar);
  A a;
  MLIB_INLINE explicit Unary(const A& a_) : a(a_) {}
  MLIB_INLINE simd::f4 eval() const { return Op::apply(a.eval()); }
  MLIB_INLINE operator float() const
    requires scalar
  {
    return simd::lane0(eval());
  }
};

template <class Op, class L, class R>
struct Binary {
  using expr_tag = void;
  static constexpr bool scalar = Op::kind == ops::Kind::reduction ||
                                 (Op::kind == ops::Kind::lanewise && L::scalar && R::scalar);
  L l;
  R r;
  MLIB_INLINE Binary(const L& l_, const R& r_) : l(l_), r(r_) {}
  MLIB_INLINE simd::f4 eval() const { return Op::apply(l.eval(), r.eval()); }
  MLIB_INLINE operator float() const
    requires scalar
  {
    return simd::lane0(eval());
  }
};

// --- turning operands into nodes -----------------------------------------------------
namespace detail {

template <class T>
struct leaf {
  using type = std::remove_cvref_t<T>;
};
template <Arithmetic T>
struct leaf<T> {
  using type = ScalarLeaf;
};
template <class T>
using leaf_t = typename leaf<T>::type;

template <Expr E>
MLIB_INLINE const E& as_expr(const E& e) {
  return e;
}
template <Arithmetic S>
MLIB_INLINE ScalarLeaf as_expr(S s) {
  return ScalarLeaf(static_cast<float>(s));
}

}  // namespace detail

// An operator applies when at least one side is an expression and the other is an
// expression or a number (scalars mix in on either side: `2.0f * n`, `n / 3`).
template <class L, class R>
concept ExprOperands = (Expr<L> || Arithmetic<L>) && (Expr<R> || Arithmetic<R>) &&
                       (Expr<L> || Expr<R>);

template <class Op, class L, class R>
MLIB_INLINE auto make_binary(const L& l, const R& r) {
  return Binary<Op, detail::leaf_t<L>, detail::leaf_t<R>>(detail::as_expr(l),
                                                          detail::as_expr(r));
}

template <class Op, Expr A>
MLIB_INLINE auto make_unary(const A& a) {
  return Unary<Op, std::remove_cvref_t<A>>(a);
}

template <class L, class R>
  requires ExprOperands<L, R>
MLIB_INLINE auto operator+(const L& l, const R& r) {
  return make_binary<ops::Add>(l, r);
}
template <class L, class R>
  requires ExprOperands<L, R>
MLIB_INLINE auto operator-(const L& l, const R& r) {
  return make_binary<ops::Sub>(l, r);
}
template <class L, class R>
  requires ExprOperands<L, R>
MLIB_INLINE auto operator*(const L& l, const R& r) {
  return make_binary<ops::Mul>(l, r);
}
template <class L, class R>
  requires ExprOperands<L, R>
MLIB_INLINE auto operator/(const L& l, const R& r) {
  return make_binary<ops::Div>(l, r);
}
template <Expr A>
MLIB_INLINE auto operator-(const A& a) {
  return make_unary<ops::Neg>(a);
}

// --- comparisons: true when the relation holds in ALL four lanes ----------------------
// Ordered IEEE semantics per lane: a NaN lane makes ==, <, <=, >, >= false, and != true
// (!= is exactly !(a == b)). +0 == -0. Because a scalar node holds its value in every
// lane, `dot(a, b) > 0.0f` means what it says.
template <class L, class R>
  requires ExprOperands<L, R>
MLIB_INLINE bool operator==(const L& l, const R& r) {
  return simd::all(simd::cmp_eq(detail::as_expr(l).eval(), detail::as_expr(r).eval()));
}
template <class L, class R>
  requires ExprOperands<L, R>
MLIB_INLINE bool operator!=(const L& l, const R& r) {
  return !(l == r);
}
template <class L, class R>
  requires ExprOperands<L, R>
MLIB_INLINE bool operator<(const L& l, const R& r) {
  return simd::all(simd::cmp_lt(detail::as_expr(l).eval(), detail::as_expr(r).eval()));
}
template <class L, class R>
  requires ExprOperands<L, R>
MLIB_INLINE bool operator<=(const L& l, const R& r) {
  return simd::all(simd::cmp_le(detail::as_expr(l).eval(), detail::as_expr(r).eval()));
}
template <class L, class R>
  requires ExprOperands<L, R>
MLIB_INLINE bool operator>(const L& l, const R& r) {
  return simd::all(simd::cmp_gt(detail::as_expr(l).eval(), detail::as_expr(r).eval()));
}
template <class L, class R>
  requires ExprOperands<L, R>
MLIB_INLINE bool operator>=(const L& l, const R& r) {
  return simd::all(simd::cmp_ge(detail::as_expr(l).eval(), detail::as_expr(r).eval()));
}

}  // namespace mlib
