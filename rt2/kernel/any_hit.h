// rt2/kernel/any_hit.h — the surfaces a segment of a ray crosses, for one ray and for a packet
// of up to 16: the query calls the caller's cross(prim, instance) for each plane, sphere
// (twice when the segment passes through it) and triangle on (t_min, t_max), in no
// particular order, until it returns true; `instance` is kNoInstance but for a triangle of
// an instance (cross takes it as a defaulted parameter). `occluded` is the query with every surface opaque; transmittance.h
// multiplies the surfaces' transparencies. A ray with a NaN coordinate crosses nothing.
#pragma once

#include <bit>

#include "rt2/kernel/kernel.h"

#include "rt2/bvh/accel.h"
#include "rt2/kernel/instances.h"
#include "rt2/kernel/planes_spheres.h"
#include "rt2/kernel/query_rays.h"
#include "rt2/kernel/wide_traverse.h"

namespace rt2::RT2_ISA {

// Whether cross(prim) returned true for a surface on (t_min, t_max) of `ray`. Always inlined
// into its caller's loop, as closest_hit (closest_hit.h). Whether there are planes or
// spheres is asked inline, so that a scene of meshes makes no call for them.
template <bool Watertight, class Cross>
MLIB_INLINE bool any_hit(const Accel& acc, const Ray& ray, float t_min, float t_max, Cross&& cross,
                         TraversalCounts* counts = nullptr) {
  if (has_nan(ray)) return false;
  if (has_planes_or_spheres(acc) && cross_planes_and_spheres(acc, ray, t_min, t_max, cross))
    return true;
  return any_triangle<kWidth>(acc.wide<kWidth>(), acc.blocks.data(), ray,
                              TriangleTest<Watertight>(ray), t_min, t_max,
                              [&](std::uint32_t prim, float) { return cross(PrimRef(prim)); },
                              counts) ||
         any_instanced<Watertight>(acc, ray, t_min, t_max, cross, counts);
}

// Whether anything at all (every surface opaque) lies on `ray` in (t_min, t_max).
template <bool Watertight>
MLIB_INLINE bool occluded(const Accel& acc, const Ray& ray, float t_min, float t_max,
                          TraversalCounts* counts = nullptr) {
  return any_hit<Watertight>(
      acc, ray, t_min, t_max, [](PrimRef, std::uint32_t = kNoInstance) { return true; }, counts);
}

// any_hit for each ray of a packet loaded into pr whose lane is in `finite` (load_finite's
// answer): cross(l, prim, instance) for lane l's surfaces; returns the lanes for which it
// returned true. Planes and spheres are tested kRayLanes rays at a time, the triangles
// walked as one packet when the rays allow it, and so the instances' trees. t_max holds kPacketSize floats (all read; those outside
// `finite` are not used).
template <bool Watertight, class Cross>
inline PacketMask any_hit_loaded(const Accel& acc, PacketRays<kWidth>& pr, PacketMask finite,
                                 float t_min, const float* t_max, Cross&& cross,
                                 TraversalCounts* counts) {
  if (!finite) return 0;
  PacketMask blocked = cross_planes_and_spheres_packet(acc, pr, finite, t_min, t_max, cross);
  const PacketMask open = finite & ~blocked;
  const WideBvh<kWidth>& bvh = acc.wide<kWidth>();
  if (!open) return blocked;
  const auto instanced = [&] {
    blocked |= any_instanced_packet<Watertight>(acc, pr, finite & ~blocked, t_min, t_max, cross,
                                                counts);
  };
  if (bvh.root == kNoChild) {
    instanced();
    return blocked;
  }
  const PacketMask walked =
      walk_as_packets(pr, open, [&](const PacketRays<kWidth>& p, PacketMask group) {
        const PacketTestFor<Watertight> pt(p, group);
        blocked |= any_triangle_packet<kWidth>(
            bvh, acc.blocks.data(), p, pt.test, group, t_min, t_max,
            [&](int l, std::uint32_t prim, float) { return cross(l, PrimRef(prim)); }, counts);
      });
  for (PacketMask m = open & ~walked; m; m &= m - 1) {
    const int l = std::countr_zero(m);
    const Ray ray = pr.ray(l);
    if (any_triangle<kWidth>(bvh, acc.blocks.data(), ray, TriangleTest<Watertight>(ray), t_min,
                             t_max[l],
                             [&](std::uint32_t prim, float) { return cross(l, PrimRef(prim)); },
                             counts))
      blocked |= PacketMask(1) << l;
  }
  instanced();
  return blocked;
}

// The rays of a packet (lanes of `lanes`) that something opaque blocks, as occluded says
// for each.
template <bool Watertight>
inline PacketMask occluded_packet(const Accel& acc, const Ray* rays, PacketMask lanes,
                                  float t_min, const float* t_max,
                                  TraversalCounts* counts = nullptr) {
  LoadedPacket p(rays, lanes, t_max);
  return any_hit_loaded<Watertight>(
      acc, p.rays, p.finite, t_min, p.bound,
      [](int, PrimRef, std::uint32_t = kNoInstance) { return true; }, counts);
}

}  // namespace rt2::RT2_ISA
