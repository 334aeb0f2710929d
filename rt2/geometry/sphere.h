// rt2/geometry/sphere.h — the sphere |X - C|^2 = r^2 (thesis 3.5.2), with the thesis's bug
// fixed and a numerically stable root.
//
// THE THESIS HAS A BUG: it writes c = 2 (P - C, P - C) - r^2; the constant term of
// |P + tD - C|^2 = r^2 is c = (P - C, P - C) - r^2.
// Stability (Haines et al., "Precision Improvements for Ray/Sphere Intersection", Ray
// Tracing Gems ch. 7): with D unit and oc = P - C, b = D·oc; the discriminant is
// r^2 - |oc - b D|^2 instead of b^2 - c, which cancels catastrophically for a small sphere
// far from the origin; the roots come from q = -(b + sign(b) sqrt(disc)) as c / q and q, so
// the smaller is not a difference of nearly equal numbers.
#pragma once

#include <cmath>

#include "rt2/geometry/ray.h"

namespace rt2 {

struct Sphere {
  vec4 center;  // w = 0
  float radius = 1.0f;
};

namespace detail {
// The nearest root in (t_min, t_max), in double precision. Even the stable form cannot
// resolve a sphere much smaller than its distance: the perpendicular oc - b D is a
// difference of two vectors of length |oc| and carries an error of about ulp(|oc|), which
// for r = 1e-4 at 1e4 (ulp 1e-3) is ten times the radius. So when r < |oc| / 100 the test
// is done here, where the same error is 2^29 times smaller; out of line (sphere.cpp), a
// rarely taken branch (rays far from a small sphere).
bool intersect_sphere_double(const Sphere& s, const Ray& r, float t_min, float t_max, float& t);
}  // namespace detail

// The nearest root in (t_min, t_max), for a unit-length ray direction.
MLIB_INLINE bool intersect(const Sphere& s, const Ray& r, float t_min, float t_max, float& t) {
  const vec4 oc = r.org - s.center;
  const float r2 = s.radius * s.radius;
  const float oc2 = dot(oc, oc);
  if (__builtin_expect(r2 * 1e4f < oc2, 0))  // r < |oc| / 100: ill-conditioned in float
    return detail::intersect_sphere_double(s, r, t_min, t_max, t);
  const float b = dot(r.dir, oc);
  const vec4 perp = oc - r.dir * b;
  const float disc = r2 - float(dot(perp, perp));
  if (!(disc >= 0.0f)) return false;  // also rejects NaN
  const float c = oc2 - r2;
  const float q = -(b + std::copysign(std::sqrt(disc), b));
  float t0 = c / q, t1 = q;
  if (t0 > t1) std::swap(t0, t1);
  if (t0 > t_min && t0 < t_max) {
    t = t0;
    return true;
  }
  if (t1 > t_min && t1 < t_max) {
    t = t1;
    return true;
  }
  return false;
}

MLIB_INLINE vec4 sphere_normal(const Sphere& s, const vec4& p) {
  return normalize(p - s.center);
}

}  // namespace rt2
