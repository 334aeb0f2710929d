// mlib/vec4.cpp — the out-of-line parts of vec4: formatting, and normalize's slow path.
#include <cstdio>
#include <string>

#include "mlib/vec4_functions.h"

namespace mlib {

std::string str(const vec4& v) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "(%.9g, %.9g, %.9g, %.9g)", static_cast<double>(v[0]),
                static_cast<double>(v[1]), static_cast<double>(v[2]),
                static_cast<double>(v[3]));
  return buf;
}

namespace ops {

// normalize of a vector whose squared length over- or underflows: scaled by its largest
// component first (see Normalize in ops.h).
simd::f4 Normalize::rescaled(simd::f4 a) {
  const simd::f4 m = simd::abs(a);
  if (!simd::all(simd::cmp_lt(m, simd::set1(__builtin_inff()))))  // false for NaN too
    return simd::set1(__builtin_nanf(""));
  const simd::f4 m2 = simd::max(m, simd::shuffle<2, 3, 0, 1>(m));
  const simd::f4 big = simd::max(m2, simd::shuffle<1, 0, 3, 2>(m2));  // max |lane|, broadcast
  if (simd::lane0(big) == 0.0f) return a;
  const simd::f4 s = simd::div(a, big);
  return simd::div(s, simd::sqrt(simd::dp_bcast(s, s)));
}

}  // namespace ops
}  // namespace mlib
