// rt2/kernel/query_rays.h — rays as the queries (closest_hit.h, any_hit.h) take them: the
// triangle test a ray gets, rays with a NaN coordinate (which hit nothing), and packets of up
// to 16 rays loaded, bounded and split by octant for the packet walks (packet_traverse.h).
#pragma once

#include <array>
#include <bit>
#include <type_traits>

#include "rt2/kernel/kernel.h"

#include "rt2/kernel/packet_traverse.h"
#include "rt2/kernel/plane_sphere_packet_intersect.h"

namespace rt2::RT2_ISA {

// The 8- and 16-wide kernels push children in octant order (wide_traverse.h); a build that
// lost mlib's compress_in_order would fall back to sorting without a word.
static_assert(kWidth == 4 || kPushInOctantOrder<kWidth>, "mlib::compress_in_order is missing");

template <bool Watertight>
using TriangleTest = std::conditional_t<Watertight, WatertightTriangleTest, FastTriangleTest>;

// The leaf test of a packet walk (triangle_packet_intersect.h), set up for the rays of
// `lanes` of a packet loaded into pr.
template <bool Watertight>
struct PacketTestFor {
  FastPacketTest<kRayLanes> test;
  PacketTestFor(const PacketRays<kWidth>& pr, PacketMask) : test{{pr.org, pr.dir}} {}
};
template <>
struct PacketTestFor<true> {
  WatertightPacketTest<kRayLanes> test;
  PacketTestFor(const PacketRays<kWidth>& pr, PacketMask lanes)
      : test(pr.org, pr.dir, [&pr](int l) { return pr.ray(l); }, lanes) {}
};

// Whether any coordinate of the ray is NaN: such a ray hits nothing (and would otherwise
// enter every box, NaN slab distances counting as inside).
inline bool has_nan(const Ray& r) {
  return !(r.org == r.org) || !(r.dir == r.dir);  // vec4 == is false when any lane is NaN
}

// The bounds of a packet's lanes, as the packet steps read them (kPacketSize floats): t_max[l]
// for the lanes l of `lanes` (only those of t_max are read), 0 for the others.
inline void lane_bounds(PacketMask lanes, const float* t_max, float* bound) {
  for (int l = 0; l < kPacketSize; ++l) bound[l] = lanes >> l & 1 ? t_max[l] : 0.0f;
}

// Below this many rays a packet's rays walk one by one: setting the packet up (its
// frustum, its leaf test) would cost more than sharing the walk saves.
inline constexpr int kMinPacketRays = 4;

// Loads the rays of `lanes` without a NaN coordinate into pr (which such a ray hits
// nothing) and returns their lanes; load(pr, lanes) loads rays (PacketRays::load).
template <class Load>
inline PacketMask load_finite(PacketRays<kWidth>& pr, PacketMask lanes, Load&& load) {
  const PacketMask finite = load(pr, lanes);
  return finite == lanes || finite == 0 ? finite : load(pr, finite);
}

// rays[l] for the lanes l of `lanes` loaded for a packet query: `finite`, the lanes without a
// NaN coordinate (load_finite), and `bound`, their t_max[l] (lane_bounds).
struct LoadedPacket {
  PacketRays<kWidth> rays;
  PacketMask finite;
  alignas(64) float bound[kPacketSize];
  LoadedPacket(const Ray* r, PacketMask lanes, const float* t_max)
      : finite(load_finite(rays, lanes,
                           [r](PacketRays<kWidth>& p, PacketMask m) { return p.load(r, m); })) {
    lane_bounds(lanes, t_max, bound);
  }
};

// Rays c ... c + kRayLanes - 1 of a loaded packet.
inline RayLanes<mlib::vfloat<kRayLanes>> ray_lanes(const PacketRays<kWidth>& pr, int c) {
  using V = mlib::vfloat<kRayLanes>;
  RayLanes<V> r;
  for (int a = 0; a < 3; ++a) {
    r.o[a] = V::load(pr.org[a] + c);
    r.d[a] = V::load(pr.dir[a] + c);
  }
  return r;
}

// The lanes of `lanes` of a loaded packet split by their directions' octant (the signs of
// x, y, z; a zero component counts as positive here, and such a ray's group then fails
// make_frustum).
inline std::array<PacketMask, 8> octant_groups(const PacketRays<kWidth>& pr, PacketMask lanes) {
  using R = mlib::vfloat<kRayLanes>;
  PacketMask negative[3] = {0, 0, 0};
  for (int c = 0; c < kPacketSize; c += kRayLanes)
    for (int a = 0; a < 3; ++a)
      negative[a] |= PacketMask(mlib::bits(R::load(pr.dir[a] + c) < R::broadcast(0.0f))) << c;
  std::array<PacketMask, 8> groups;
  for (int o = 0; o < 8; ++o)
    groups[o] = lanes & (o & 1 ? negative[0] : ~negative[0]) &
                (o & 2 ? negative[1] : ~negative[1]) & (o & 4 ? negative[2] : ~negative[2]);
  return groups;
}

// Walks the rays of `lanes` (loaded into pr) as packets where they can: all together when
// there are enough of them and their directions share signs, else one smaller packet per
// octant with at least kMinPacketRays rays. walk(packet_rays, group) walks one packet;
// returns the lanes walked, the caller takes the others one by one.
template <class Walk>
inline PacketMask walk_as_packets(PacketRays<kWidth>& pr, PacketMask lanes, Walk&& walk) {
  if (std::popcount(lanes) < kMinPacketRays) return 0;
  if (pr.make_frustum()) {
    walk(pr, lanes);
    return lanes;
  }
  // Rays of mixed directions (reflections off a curved surface, a tile across an axis).
  PacketMask walked = 0;
  if (std::popcount(lanes) < 2 * kMinPacketRays) return walked;
  for (const PacketMask group : octant_groups(pr, lanes)) {
    if (std::popcount(group) < kMinPacketRays) continue;
    PacketRays<kWidth> sub;
    sub.load(pr, group);
    if (!sub.make_frustum()) continue;
    walk(sub, group);
    walked |= group;
  }
  return walked;
}

}  // namespace rt2::RT2_ISA
