// rt2/kernel/closest_hit.h — the closest hit along a ray over planes, spheres and triangles,
// for one ray and for a packet of up to 16 (each ray's answer bit for bit the same either
// way): t = inf and prim = kNoHit when there is none.
#pragma once

#include <bit>
#include <cstring>

#include "rt2/kernel/kernel.h"

#include "rt2/bvh/accel.h"
#include "rt2/kernel/instances.h"
#include "rt2/kernel/planes_spheres.h"
#include "rt2/kernel/query_rays.h"
#include "rt2/kernel/wide_traverse.h"

namespace rt2::RT2_ISA {

// The closest hit in (t_min, t_max) over planes, spheres, triangles and instances; t = inf
// and prim = kNoHit when there is none.
//
// Always inlined into its caller's loop: out of line, GCC 12 returns the Hit through the
// stack as 4- and 8-byte stores read back as two 8-byte halves, a load that no store can
// forward, once per ray; inlined, the Hit stays in registers.
template <bool Watertight>
MLIB_INLINE Hit closest_hit(const Accel& acc, const Ray& ray, float t_min, float t_max,
                            TraversalCounts* counts = nullptr) {
  Hit h;
  h.t = t_max;
  if (has_nan(ray)) {
    h.t = kInfinity;
    return h;
  }
  closest_plane_or_sphere(acc, ray, t_min, h);
  closest_triangle<kWidth>(acc.wide<kWidth>(), acc.blocks.data(), ray, TriangleTest<Watertight>(ray),
                           t_min, h, counts);
  closest_instanced<Watertight>(acc, ray, t_min, h, counts);
  // A miss as a fresh value: h is in memory when an instance walk took it (a field stored
  // alone, then the whole read back, is a load no store can forward).
  if (!h.found()) return Hit{};
  return h;
}

// closest_hit for each ray of a packet loaded into pr: hits[l] = closest_hit(acc, ray l,
// t_min, t_max[l]) for the lanes l of `lanes` (bit for bit the same; `finite`: those
// without a NaN coordinate, load_finite's answer), planes and spheres tested kRayLanes rays
// at a time, the triangles walked as one packet when the rays allow it
// (packet_traverse.h), and so the instances' trees. t_max holds kPacketSize floats (all read; those outside `lanes` are
// not used); only the lanes of `lanes` of hits are written.
template <bool Watertight>
inline void closest_hit_loaded(const Accel& acc, PacketRays<kWidth>& pr, PacketMask lanes,
                               PacketMask finite, float t_min, const float* t_max, Hit* hits,
                               TraversalCounts* counts) {
  for (PacketMask m = lanes; m; m &= m - 1) {
    const int l = std::countr_zero(m);
    hits[l] = Hit{};
    if (finite >> l & 1) hits[l].t = t_max[l];
  }
  if (finite) {
    // Each ray's bound: t_max, then its plane or sphere hit (the triangles' walk starts there).
    alignas(64) float t_bound[kPacketSize];
    std::memcpy(t_bound, t_max, sizeof t_bound);  // whole vectors, as they are read
    closest_plane_or_sphere_packet(acc, pr, finite, t_min, hits, t_bound);
    const WideBvh<kWidth>& bvh = acc.wide<kWidth>();
    if (bvh.root == kNoChild) {
      // no triangles
    } else {
      const PacketMask walked =
          walk_as_packets(pr, finite, [&](const PacketRays<kWidth>& p, PacketMask group) {
            const PacketTestFor<Watertight> pt(p, group);
            closest_triangle_packet<kWidth>(bvh, acc.blocks.data(), p, pt.test, group, t_min,
                                            t_bound, hits, counts);
          });
      for (PacketMask m = finite & ~walked; m; m &= m - 1) {
        const int l = std::countr_zero(m);
        const Ray ray = pr.ray(l);
        closest_triangle<kWidth>(bvh, acc.blocks.data(), ray, TriangleTest<Watertight>(ray), t_min,
                                 hits[l], counts);
      }
    }
    closest_instanced_packet<Watertight>(acc, pr, finite, t_min, hits, counts);
  }
  for (PacketMask m = lanes; m; m &= m - 1) {
    const int l = std::countr_zero(m);
    if (!hits[l].found()) hits[l].t = kInfinity;
  }
}

// closest_hit_loaded for rays[l], l in `lanes`.
template <bool Watertight>
inline void closest_hit_packet(const Accel& acc, const Ray* rays, PacketMask lanes, float t_min,
                               const float* t_max, Hit* hits, TraversalCounts* counts = nullptr) {
  LoadedPacket p(rays, lanes, t_max);
  closest_hit_loaded<Watertight>(acc, p.rays, lanes, p.finite, t_min, p.bound, hits, counts);
}

// closest_hit_loaded for the rays first + l of columns, l in `lanes` (the columns are read
// at first ... first + kPacketSize - 1, and t_max's kPacketSize floats).
template <bool Watertight>
inline void closest_hit_packet(const Accel& acc, const RayColumns& rays, std::size_t first,
                               PacketMask lanes, float t_min, const float* t_max, Hit* hits,
                               TraversalCounts* counts = nullptr) {
  PacketRays<kWidth> pr;
  const PacketMask finite = load_finite(
      pr, lanes, [&rays, first](PacketRays<kWidth>& p, PacketMask m) { return p.load(rays, first, m); });
  closest_hit_loaded<Watertight>(acc, pr, lanes, finite, t_min, t_max, hits, counts);
}

}  // namespace rt2::RT2_ISA
