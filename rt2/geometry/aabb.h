// rt2/geometry/aabb.h — axis-aligned bounding boxes and the ray/box slab test.
#pragma once

#include <algorithm>

#include "rt2/geometry/ray.h"

namespace rt2 {

struct Aabb {
  vec4 lo{kInfinity, kInfinity, kInfinity, 0.0f};
  vec4 hi{-kInfinity, -kInfinity, -kInfinity, 0.0f};

  static Aabb empty() { return {}; }
  bool is_empty() const { return !(lo[0] <= hi[0] && lo[1] <= hi[1] && lo[2] <= hi[2]); }
  void grow(const vec4& p) {
    lo = mlib::min(lo, p);
    hi = mlib::max(hi, p);
  }
  void grow(const Aabb& b) {
    lo = mlib::min(lo, b.lo);
    hi = mlib::max(hi, b.hi);
  }
  // Whether p (x, y, z; w is ignored) lies in the box, its faces included.
  bool contains(const vec4& p) const {
    const mlib::simd::f4 in = mlib::simd::bit_and(mlib::simd::cmp_le(lo.m128(), p.m128()),
                                                  mlib::simd::cmp_le(p.m128(), hi.m128()));
    return (mlib::simd::movemask(in) & 7) == 7;
  }
  vec4 extent() const { return hi - lo; }
  vec4 center() const { return (lo + hi) * 0.5f; }
  // Surface area (0 for an empty box), the SAH's measure.
  float area() const {
    if (is_empty()) return 0.0f;
    const vec4 e = extent();
    return 2.0f * (e[0] * e[1] + e[1] * e[2] + e[2] * e[0]);
  }
  int longest_axis() const {
    const vec4 e = extent();
    return e[0] >= e[1] && e[0] >= e[2] ? 0 : (e[1] >= e[2] ? 1 : 2);
  }
};

// 1 + 2 gamma(3) (Ize 2013): how much a rounded slab distance may undershoot the exact
// one. The far distance is multiplied by it; so is the closest hit when a stored entry
// distance is compared with it (rt2/bvh/traverse.h).
inline constexpr float kSlabPad = 1.0f + 2.0f * (3.0f * 0x1p-24f / (1.0f - 3.0f * 0x1p-24f));

// Slab test of lanes x y z (w is ignored). Returns the entry distance, or +inf for a miss
// of the interval [t_min, t_max].
//
// Robustness (Ize, "Robust BVH Ray Traversal", JCGT 2013): the far distance is scaled up
// by 1 + 2 gamma(3) so that rounding can never cull a box the ray touches, a grazing ray
// along a face included. A zero direction component gives an infinite reciprocal: for an
// origin inside the slab the two distances are -inf and +inf, outside both have one sign
// (a miss), and for an origin exactly on a slab plane 0 * inf is NaN. Clamping each
// distance into [-inf, +inf] with maxps / minps (which return the second operand for NaN)
// turns that NaN into the neutral bound, so a ray lying in a face plane counts as inside.
MLIB_INLINE float slab_entry(const vec4& lo, const vec4& hi, const RayPre& r, float t_min,
                        float t_max) {
  const vec4 t0 = (lo - r.org) * r.inv_dir;
  const vec4 t1 = (hi - r.org) * r.inv_dir;
  const vec4 neg_inf(-kInfinity), pos_inf(kInfinity);
  const vec4 near = mlib::min(mlib::max(t0, neg_inf), mlib::max(t1, neg_inf));
  const vec4 far = mlib::max(mlib::min(t0, pos_inf), mlib::min(t1, pos_inf));
  const float tn = std::max(t_min, mlib::hmax3(near));
  float tf = std::min(t_max, mlib::hmin3(far));
  tf *= kSlabPad;
  return tn <= tf ? tn : kInfinity;
}

}  // namespace rt2
