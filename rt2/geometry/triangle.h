// rt2/geometry/triangle.h — ray/triangle intersection: the thesis's fast test (3.5.3,
// formula 10) and the watertight test of Woop, Benthin and Wald (JCGT 2013).
//
// Stored per triangle: the three vertices exactly as given (a shared vertex has the same
// bits in every triangle, which the watertight test needs) and the unnormalised normal
// N = E2 x E1. The fast test can let a ray slip between two triangles through a shared
// edge; the watertight test cannot (each described at its function below).
#pragma once

#include <cmath>
#include <cstdint>
#include <utility>

#include "rt2/geometry/ray.h"

namespace rt2 {

// 64 bytes: four vec4s, read together by the intersection.
struct Triangle {
  vec4 v0, v1, v2;
  vec4 n;  // E2 x E1 = (V1 - V0) x (V2 - V0), not normalised (|n| = twice the area)

  static Triangle make(const vec4& a, const vec4& b, const vec4& c) {
    return Triangle{a, b, c, cross(c - a, a - b)};
  }
  const vec4& vertex(int i) const { return i == 0 ? v0 : (i == 1 ? v1 : v2); }
  // The point with barycentrics (u, v): (1 - u - v) V0 + u V1 + v V2.
  vec4 point(float u, float v) const { return v0 + u * (v1 - v0) + v * (v2 - v0); }
};
static_assert(sizeof(Triangle) == 64);

// Fast test (thesis formula 10): E1 = V0 - V1, E2 = V2 - V0, T = V0 - P, S = T x Dir,
// [t, u, v] = [T·N, S·E2, S·E1] / (Dir·N); a hit when u >= 0, v >= 0, u + v <= 1 and t is
// inside the ray's interval (u >= 0 and v >= 0 tested as the signs of S·E2 and S·E1
// relative to Dir·N, which is the same but for a quotient that underflows). Branch-free up
// to the answer; a ray parallel to the triangle divides by zero and every comparison fails.
// Each triangle rounds its own edges, so a ray through a shared edge or vertex can slip
// between two triangles. The four dot products (T·N, S·E2, S·E1, Dir·N) are computed
// together by mlib::dot4 (a transpose instead of four dpps).
inline bool intersect(const Triangle& tri, const Ray& r, float t_min, float t_max, float& t,
                      float& u, float& v) {
  const vec4 e1 = tri.v0 - tri.v1;
  const vec4 e2 = tri.v2 - tri.v0;
  const vec4 tv = tri.v0 - r.org;
  const vec4 s = cross(tv, r.dir);
  const vec4 d = dot4(tv, tri.n, s, e2, s, e1, r.dir, tri.n);
  const vec4 tuv = d / d.w();
  t = tuv.x();
  u = tuv.y();
  v = tuv.z();
  // u >= 0 and v >= 0 as signs of S·E2 and S·E1 against Dir·N (the quotient could round a
  // tiny negative to -0): the form the four-triangle test checks before it divides.
  const float side = std::copysign(1.0f, d.w());
  return (t > t_min) & (t < t_max) & (d.y() * side >= 0.0f) & (d.z() * side >= 0.0f) &
         (u + v <= 1.0f);
}

// The watertight test's axes for each combination of a direction's comparisons and signs
// (see WatertightRay): entry i holds kx | ky << 2 | kz << 4 for i = (ax > ay) | (ay > az) << 1
// | (ax > az) << 2 | (dir x < 0) << 3 | (dir y < 0) << 4 | (dir z < 0) << 5, a the absolute
// components.
struct WatertightAxes {
  std::uint8_t of[64];
};
inline constexpr WatertightAxes kWatertightAxes = [] {
  WatertightAxes t{};
  for (int i = 0; i < 64; ++i) {
    const int kz = i & 1 ? (i & 4 ? 0 : 2) : (i & 2 ? 1 : 2);
    int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
    if (i >> (3 + kz) & 1) std::swap(kx, ky);
    t.of[i] = std::uint8_t(kx | ky << 2 | kz << 4);
  }
  return t;
}();

// The per-ray part of the watertight test: the axis the ray is most aligned with becomes
// z (kz), the other two x and y (swapped when the ray goes towards -z, to keep the
// winding), and the shear that maps the ray onto +z.
struct WatertightRay {
  vec4 org;
  int kx, ky, kz;
  float sx, sy, sz;

  WatertightRay() = default;  // unset, to be assigned
  // kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2), kx = kz + 1 and ky = kz + 2
  // (mod 3), swapped when dir[kz] < 0; all read from one table (kWatertightAxes) indexed by
  // the comparisons and signs, without a branch: for random directions both choices go
  // either way at random, and mispredicted branches would slow incoherent rays, while a
  // chain of lookups (kz, then kx from kz, ...) would delay the shear of every ray. The
  // index takes two vector compares rather than six scalar ones.
  explicit WatertightRay(const Ray& r) : org(r.org) {
    namespace simd = mlib::simd;
    const simd::f4 d = r.dir.m128(), a = simd::abs(d);
    const simd::f4 greater =  // ax > ay, ay > az, ax > az
        simd::cmp_gt(simd::shuffle<0, 1, 0, 3>(a), simd::shuffle<1, 2, 2, 3>(a));
    const simd::f4 negative = simd::cmp_lt(d, simd::zero());  // false for -0 and NaN
    const unsigned axes = kWatertightAxes.of[(unsigned(simd::movemask(greater)) & 7u) |
                                             (unsigned(simd::movemask(negative)) & 7u) << 3];
    kx = int(axes & 3u);
    ky = int(axes >> 2 & 3u);
    kz = int(axes >> 4);
    sx = r.dir[kx] / r.dir[kz];
    sy = r.dir[ky] / r.dir[kz];
    sz = 1.0f / r.dir[kz];
  }
};

// Watertight test: the ray is sheared so that it runs along +z through the origin (a
// per-ray permutation and shear, WatertightRay); each triangle is projected into that 2D
// frame and the three edge functions U, V, W are evaluated from the projected vertices.
// An edge shared by two triangles yields the same products in both, so the signs agree
// exactly and no ray passes between them; an edge function that is exactly zero is
// recomputed in double precision, as the paper prescribes.
inline bool intersect_watertight(const Triangle& tri, const WatertightRay& r, float t_min,
                                 float t_max, float& t, float& u, float& v) {
  const vec4 a = tri.v0 - r.org, b = tri.v1 - r.org, c = tri.v2 - r.org;
  // Vertices in the sheared 2D frame of the ray.
  const float ax = a[r.kx] - r.sx * a[r.kz], ay = a[r.ky] - r.sy * a[r.kz];
  const float bx = b[r.kx] - r.sx * b[r.kz], by = b[r.ky] - r.sy * b[r.kz];
  const float cx = c[r.kx] - r.sx * c[r.kz], cy = c[r.ky] - r.sy * c[r.kz];
  // Edge functions: U for edge V1V2 (the weight of V0), V for V2V0, W for V0V1.
  float eu = cx * by - cy * bx;
  float ev = ax * cy - ay * cx;
  float ew = bx * ay - by * ax;
  if (eu == 0.0f || ev == 0.0f || ew == 0.0f) {  // exactly on an edge: decide in double
    eu = static_cast<float>(double(cx) * by - double(cy) * bx);
    ev = static_cast<float>(double(ax) * cy - double(ay) * cx);
    ew = static_cast<float>(double(bx) * ay - double(by) * ax);
  }
  if ((eu < 0.0f || ev < 0.0f || ew < 0.0f) && (eu > 0.0f || ev > 0.0f || ew > 0.0f))
    return false;  // outside (both faces are hit: no back-face culling)
  const float det = eu + ev + ew;
  if (!(det != 0.0f)) return false;  // parallel, degenerate or NaN
  const float az = r.sz * a[r.kz], bz = r.sz * b[r.kz], cz = r.sz * c[r.kz];
  const float inv = 1.0f / det;
  t = (eu * az + ev * bz + ew * cz) * inv;
  u = ev * inv;
  v = ew * inv;
  return t > t_min && t < t_max;
}

}  // namespace rt2
