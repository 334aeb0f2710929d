// rt2/geometry/triangle.h — ray/triangle intersection (thesis 3.5.3, formula 10).
//
// Precomputed per triangle: V0, E1 = V0 - V1, E2 = V2 - V0 and N = E2 x E1. Per ray:
// T = V0 - P, S = T x Dir and [t, u, v] = [T·N, S·E2, S·E1] / (Dir·N); a hit when
// u >= 0, v >= 0, u + v <= 1 and t is inside the ray's interval. The test is branch-free
// up to the final answer, as in the thesis (which returned b*t + b - 1); a ray parallel
// to the triangle divides by zero and every comparison fails, so it misses.
#pragma once

#include "rt2/ray.h"

namespace rt2 {

// 64 bytes: four vec4s, read together by the intersection.
struct Triangle {
  vec4 v0;
  vec4 e1;  // V0 - V1
  vec4 e2;  // V2 - V0
  vec4 n;   // E2 x E1, not normalised (|n| = twice the area)

  static Triangle make(const vec4& a, const vec4& b, const vec4& c) {
    Triangle t;
    t.v0 = a;
    t.e1 = a - b;
    t.e2 = c - a;
    t.n = cross(t.e2, t.e1);
    return t;
  }
  vec4 vertex(int i) const { return i == 0 ? v0 : (i == 1 ? vec4(v0 - e1) : vec4(v0 + e2)); }
};
static_assert(sizeof(Triangle) == 64);

// The four dot products (T·N, S·E2, S·E1, Dir·N) are computed together by mlib::dot4 (a
// transpose instead of four dpps).
inline bool intersect(const Triangle& tri, const Ray& r, float t_min, float t_max, float& t,
                      float& u, float& v) {
  const vec4 tv = tri.v0 - r.org;
  const vec4 s = cross(tv, r.dir);
  const vec4 d = dot4(tv, tri.n, s, tri.e2, s, tri.e1, r.dir, tri.n);
  const vec4 tuv = d / d.w();
  t = tuv.x();
  u = tuv.y();
  v = tuv.z();
  return (t > t_min) & (t < t_max) & (u >= 0.0f) & (v >= 0.0f) & (u + v <= 1.0f);
}

}  // namespace rt2
