// rt2/kernel/instances.h — the top level of the two-level tree (rt2/bvh/accel.h): a ray
// walks the binary tree over the instances' world boxes and, in each instance it enters,
// its mesh's wide tree in the mesh's coordinates, with the same walks as the world's
// triangles. The ray is transformed, not renormalised: t stays the world's distance.
#pragma once

#include <cstdint>

#include "rt2/kernel/kernel.h"

#include "rt2/bvh/accel.h"
#include "rt2/bvh/traverse.h"
#include "rt2/kernel/query_rays.h"
#include "rt2/kernel/wide_traverse.h"

namespace rt2::RT2_ISA {

// `ray` in instance `in`'s coordinates; false when the transform makes a coordinate
// infinite or NaN (such a ray meets nothing in the instance).
MLIB_INLINE bool enter_instance(const TracedInstance& in, const Ray& ray, Ray& local) {
  if (in.identity) {
    local = ray;
    return true;
  }
  local = Ray(in.to_object.point(ray.org), in.to_object.direction(ray.dir));
  const vec4 zero(0.0f, 0.0f, 0.0f, 0.0f);
  return (local.org - local.org) == zero && (local.dir - local.dir) == zero;
}

// The closest triangle of any instance nearer than h.t (ties: closest_triangle) into h, with
// h.instance naming the instance.
template <bool Watertight>
MLIB_INLINE void closest_instanced(const Accel& acc, const Ray& ray, float t_min, Hit& h,
                                   TraversalCounts* counts) {
  if (acc.instances.empty()) return;
  float t_far = h.t;
  traverse<false>(acc.instance_bvh, RayPre(ray), t_min, t_far,
                  [&](std::uint32_t first, std::uint32_t count, float& t_max) {
                    for (std::uint32_t i = first; i < first + count; ++i) {
                      const TracedInstance& in = acc.instances[i];
                      Ray local;
                      if (!enter_instance(in, ray, local)) continue;
                      if (closest_triangle<kWidth>(acc.mesh_tree<kWidth>(in.mesh),
                                                   acc.blocks.data(), local,
                                                   TriangleTest<Watertight>(local), t_min, h,
                                                   counts, i))
                        t_max = h.t;
                    }
                    return false;
                  });
}

// Calls cross(prim, instance) for the instances' triangles on (t_min, t_max) of `ray`, in
// no particular order, until it returns true; returns whether it did.
template <bool Watertight, class Cross>
MLIB_INLINE bool any_instanced(const Accel& acc, const Ray& ray, float t_min, float t_max,
                               Cross&& cross, TraversalCounts* counts) {
  if (acc.instances.empty()) return false;
  bool stopped = false;
  float t_far = t_max;
  traverse<true>(acc.instance_bvh, RayPre(ray), t_min, t_far,
                 [&](std::uint32_t first, std::uint32_t count, float&) {
                   for (std::uint32_t i = first; i < first + count && !stopped; ++i) {
                     const TracedInstance& in = acc.instances[i];
                     Ray local;
                     if (!enter_instance(in, ray, local)) continue;
                     stopped = any_triangle<kWidth>(
                         acc.mesh_tree<kWidth>(in.mesh), acc.blocks.data(), local,
                         TriangleTest<Watertight>(local), t_min, t_max,
                         [&](std::uint32_t prim, float) { return cross(PrimRef(prim), i); },
                         counts);
                   }
                   return stopped;
                 });
  return stopped;
}

}  // namespace rt2::RT2_ISA
