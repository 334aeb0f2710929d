// rt2/geometry/plane.h — the plane N·X + D = 0 (thesis 3.5.1).
#pragma once

#include "rt2/geometry/ray.h"

namespace rt2 {

struct Plane {
  vec4 n;          // unit normal, w = 0
  float d = 0.0f;  // N·X + D = 0 for points X on the plane
};

// t = -(P·N + D) / (Dir·N). A ray parallel to the plane (Dir·N = 0) gives ±inf or NaN and
// fails the interval test, so it misses — no branch needed.
MLIB_INLINE bool intersect(const Plane& pl, const Ray& r, float t_min, float t_max, float& t) {
  const float denom = dot(r.dir, pl.n);
  t = -(float(dot(r.org, pl.n)) + pl.d) / denom;
  return t > t_min && t < t_max;
}

}  // namespace rt2
