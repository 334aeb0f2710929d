// rt2/query.h — what the renderer asks of the geometry: the closest hit along a ray, and how
// much light passes along a shadow ray.
//
// Both combine the three kinds of primitive: planes (a loop: they are unbounded), spheres
// (their binary tree, bvh/traverse.h) and triangles (the wide tree, bvh/wide_traverse.h),
// with the triangle test chosen by `Watertight`. Compiled per instruction set (rt2/isa.h):
// the code lives in rt2::RT2_ISA, and the ISA's BVH width is fixed here at compile time.
#pragma once

#include <utility>
#include <vector>

#include "rt2/accel.h"
#include "rt2/isa.h"
#include "rt2/bvh/traverse.h"
#include "rt2/bvh/wide_traverse.h"

namespace rt2::RT2_ISA {

// The BVH width of this instruction set (the enumerators are named as the namespaces).
inline constexpr int kWidth = bvh_width(Isa::RT2_ISA);

template <bool Watertight>
using TriangleTest = std::conditional_t<Watertight, WatertightTriangleTest, FastTriangleTest>;

// Whether any coordinate of the ray is NaN: such a ray hits nothing (and would otherwise
// enter every box, NaN slab distances counting as inside).
inline bool has_nan(const Ray& r) {
  return !(r.org == r.org) || !(r.dir == r.dir);  // vec4 == is false when any lane is NaN
}

// Calls leaf(first, count, t_max) for the leaves of the spheres' tree that the ray may hit,
// nearest first, as bvh/traverse.h does. A tree that is a single leaf (up to
// max_leaf_size spheres, the usual scene) is tested without the walk's set-up.
template <bool AnyHit, class Leaf>
MLIB_INLINE void sphere_leaves(const Accel& acc, const Ray& ray, float t_min, float& t_max,
                               Leaf&& leaf) {
  if (acc.spheres.empty()) return;
  const BvhNode& root = acc.sphere_bvh.nodes[0];
  if (root.is_leaf()) {
    leaf(root.offset, root.count, t_max);
    return;
  }
  traverse<AnyHit>(acc.sphere_bvh, RayPre(ray), t_min, t_max, leaf);
}

// The closest hit in (t_min, t_max) over planes, spheres and triangles; t = inf and
// prim = kNoHit when there is none.
template <bool Watertight>
inline Hit closest_hit(const Accel& acc, const Ray& ray, float t_min, float t_max,
                       TraversalCounts* counts = nullptr) {
  Hit h;
  h.t = t_max;
  if (has_nan(ray)) {
    h.t = kInfinity;
    return h;
  }
  // Planes and spheres are tested in the same order by every ISA; triangles, whose order
  // depends on the tree's width, break ties by index (and win ties against the others).
  for (std::uint32_t i = 0; i < acc.planes.size(); ++i) {
    float t;
    if (intersect(acc.planes[i], ray, t_min, h.t, t)) {
      h.t = t;
      h.prim = kPlaneTag | i;
    }
  }
  float t_far = h.t;
  sphere_leaves<false>(acc, ray, t_min, t_far,
                       [&](std::uint32_t first, std::uint32_t count, float& t_max_) {
                         for (std::uint32_t i = first; i < first + count; ++i) {
                           float t;
                           if (intersect(acc.spheres[i], ray, t_min, t_max_, t)) {
                             t_max_ = h.t = t;
                             h.prim = kSphereTag | i;
                           }
                         }
                         return false;
                       });
  closest_triangle<kWidth>(acc.wide<kWidth>(), acc.blocks.data(), ray, TriangleTest<Watertight>(ray),
                           t_min, h, counts);
  if (!h.found()) h.t = kInfinity;
  return h;
}

// Whether anything at all (every surface opaque) lies on `ray` in (t_min, t_max).
template <bool Watertight>
inline bool occluded(const Accel& acc, const Ray& ray, float t_min, float t_max,
                     TraversalCounts* counts = nullptr) {
  if (has_nan(ray)) return false;
  for (const Plane& p : acc.planes) {
    float t;
    if (intersect(p, ray, t_min, t_max, t)) return true;
  }
  float t_far = t_max;
  bool hit = false;
  sphere_leaves<true>(acc, ray, t_min, t_far,
                      [&](std::uint32_t first, std::uint32_t count, float&) {
                        for (std::uint32_t i = first; i < first + count && !hit; ++i) {
                          float t;
                          hit = intersect(acc.spheres[i], ray, t_min, t_max, t);
                        }
                        return hit;
                      });
  if (hit) return true;
  return any_triangle<kWidth>(acc.wide<kWidth>(), acc.blocks.data(), ray, TriangleTest<Watertight>(ray),
                              t_min, t_max, [](std::uint32_t, float) { return true; }, counts);
}

// How much light passes along the segment (t_min, t_max) of `ray`: 1 when nothing is in
// the way, 0 when an opaque surface is, and the product of the transparencies Kt of every
// surface crossed otherwise (each crossing counts once: a glass sphere crossed through
// attenuates twice, as a closed glass mesh does). The product does not depend on the order
// the crossings are found in (they are sorted first, up to 16 of them), so every ISA and
// BVH width gives the same value.
template <bool Watertight>
inline float transmittance(const Accel& acc, const std::vector<Material>& materials,
                           const Ray& ray, float t_min, float t_max,
                           TraversalCounts* counts = nullptr) {
  if (has_nan(ray)) return 1.0f;
  constexpr int kKept = 16;
  float factors[kKept];
  int kept = 0;
  float overflow = 1.0f;  // beyond kKept crossings (never seen in practice): in found order
  // Returns true when no light can pass any more.
  auto crossing = [&](std::uint32_t material) {
    const float k = materials[material].transparency;
    if (k == 0.0f) return true;
    if (kept < kKept)
      factors[kept++] = k;
    else
      overflow *= k;
    return false;
  };
  for (std::uint32_t i = 0; i < acc.planes.size(); ++i) {
    float t;
    if (intersect(acc.planes[i], ray, t_min, t_max, t) && crossing(acc.plane_materials[i]))
      return 0.0f;
  }
  float t_far = t_max;
  bool blocked = false;
  sphere_leaves<true>(acc, ray, t_min, t_far,
                      [&](std::uint32_t first, std::uint32_t count, float&) {
                        for (std::uint32_t i = first; i < first + count && !blocked; ++i) {
                          float t, t2;
                          if (!intersect(acc.spheres[i], ray, t_min, t_max, t)) continue;
                          blocked = crossing(acc.sphere_materials[i]);
                          // The far side of a sphere is a second crossing.
                          if (!blocked && intersect(acc.spheres[i], ray, t, t_max, t2))
                            blocked = crossing(acc.sphere_materials[i]);
                        }
                        return blocked;
                      });
  if (blocked) return 0.0f;
  const TriangleTest<Watertight> test(ray);
  if (any_triangle<kWidth>(acc.wide<kWidth>(), acc.blocks.data(), ray, test, t_min, t_max,
                           [&](std::uint32_t prim, float) { return crossing(acc.tri_materials[prim]); },
                           counts))
    return 0.0f;
  for (int i = 1; i < kept; ++i)  // ascending (insertion sort: kept is small)
    for (int j = i; j > 0 && factors[j] < factors[j - 1]; --j) std::swap(factors[j], factors[j - 1]);
  float tr = 1.0f;
  for (int i = 0; i < kept; ++i) tr *= factors[i];
  return tr * overflow;
}

}  // namespace rt2::RT2_ISA
