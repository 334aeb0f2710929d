// mlib/ops.h — the operations an expression node can apply, as small stateless functors.
//
// Each functor has a static `apply` on simd::f4 values and a `kind` that tells the node
// whether its result is a scalar (the same value in all four lanes, convertible to float):
//   lanewise  — scalar exactly when every operand is scalar (2 * dot(a, b) stays scalar);
//   reduction — always scalar (dot);
//   vectorial — never scalar, whatever its operands (cross, normalize).
#pragma once

#include "mlib/simd.h"

namespace mlib::ops {

enum class Kind { lanewise, reduction, vectorial };

using simd::f4;

struct Add {
  static constexpr Kind kind = Kind::lanewise;
  static MLIB_INLINE f4 apply(f4 a, f4 b) { return simd::add(a, b); }
};
struct Sub {
  static constexpr Kind kind = Kind::lanewise;
  static MLIB_INLINE f4 apply(f4 a, f4 b) { return simd::sub(a, b); }
};
struct Mul {
  static constexpr Kind kind = Kind::lanewise;
  static MLIB_INLINE f4 apply(f4 a, f4 b) { return simd::mul(a, b); }
};
struct Div {
  static constexpr Kind kind = Kind::lanewise;
  static MLIB_INLINE f4 apply(f4 a, f4 b) { return simd::div(a, b); }
};
struct Min {  // NaN in either lane gives b's lane (minps)
  static constexpr Kind kind = Kind::lanewise;
  static MLIB_INLINE f4 apply(f4 a, f4 b) { return simd::min(a, b); }
};
struct Max {  // NaN in either lane gives b's lane (maxps)
  static constexpr Kind kind = Kind::lanewise;
  static MLIB_INLINE f4 apply(f4 a, f4 b) { return simd::max(a, b); }
};
struct Dot {  // four-lane dot product, broadcast (dpps mask 0xFF)
  static constexpr Kind kind = Kind::reduction;
  static MLIB_INLINE f4 apply(f4 a, f4 b) { return simd::dp_bcast(a, b); }
};
struct Cross {  // 3D cross product of x y z; w = 0 for finite inputs
  static constexpr Kind kind = Kind::vectorial;
  static MLIB_INLINE f4 apply(f4 a, f4 b) { return simd::cross(a, b); }
};

struct Neg {
  static constexpr Kind kind = Kind::lanewise;
  static MLIB_INLINE f4 apply(f4 a) { return simd::neg(a); }
};
struct Abs {
  static constexpr Kind kind = Kind::lanewise;
  static MLIB_INLINE f4 apply(f4 a) { return simd::abs(a); }
};
struct Sqrt {
  static constexpr Kind kind = Kind::lanewise;
  static MLIB_INLINE f4 apply(f4 a) { return simd::sqrt(a); }
};
// a / |a| over all four lanes, accurate to a few ulp for every finite nonzero input. The
// fast path divides by sqrt(dot(a, a)) while that is a normal float (1.1e-19 < |a| <
// 1.8e19); outside it (a rarely taken, well-predicted branch) the vector is first scaled
// by its largest |lane| so that the square neither overflows nor underflows.
// A zero vector (of +0 or -0 lanes) is returned unchanged, not NaN. A vector with a NaN or
// infinite lane gives NaN in every lane.
struct Normalize {
  static constexpr Kind kind = Kind::vectorial;
  static MLIB_INLINE f4 apply(f4 a) {
    const f4 len2 = simd::dp_bcast(a, a);
    const float l2 = simd::lane0(len2);
    if (__builtin_expect(l2 >= 1.17549435e-38f && l2 <= 3.40282347e38f, 1))
      return simd::div(a, simd::sqrt(len2));
    return rescaled(a);
  }

 private:
  // Out of line (vec4.cpp): compiled once, for the baseline instruction set, so that the
  // translation units built for wider sets (rt2/base/isa.h) never hold a copy of their own.
  [[gnu::cold]] static f4 rescaled(f4 a);
};

}  // namespace mlib::ops
