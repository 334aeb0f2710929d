// rt2/kernel/query.h — what the renderer asks of the geometry: the closest hit along a ray, and how
// much light passes along a shadow ray.
//
// Both combine the three kinds of primitive: planes (a loop: they are unbounded), spheres
// (their binary tree, bvh/traverse.h) and triangles (the wide tree, bvh/wide_traverse.h),
// with the triangle test chosen by `Watertight`. Compiled per instruction set (rt2/base/isa.h):
// the code lives in rt2::RT2_ISA, and the ISA's BVH width is fixed here at compile time.
#pragma once

#include <array>
#include <bit>
#include <cstring>
#include <utility>
#include <vector>

#include "rt2/bvh/accel.h"
#include "rt2/base/isa.h"
#include "rt2/kernel/packet_traverse.h"
#include "rt2/bvh/traverse.h"
#include "rt2/kernel/wide_traverse.h"
#include "rt2/kernel/plane_sphere_packet_intersect.h"

namespace rt2::RT2_ISA {

// The BVH width of this instruction set (the enumerators are named as the namespaces).
inline constexpr int kWidth = bvh_width(Isa::RT2_ISA);
// The 8- and 16-wide kernels push children in octant order (wide_traverse.h); a build that lost
// mlib's compress_in_order would fall back to sorting without a word.
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

// Whether the scene has planes or spheres.
MLIB_INLINE bool has_planes_or_spheres(const Accel& acc) {
  return !(acc.planes.empty() && acc.spheres.empty());
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

namespace detail {
// closest_plane_or_sphere's tests, for a scene that has planes or spheres.
inline void closest_of_planes_and_spheres(const Accel& acc, const Ray& ray, float t_min, Hit& h) {
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
}
}  // namespace detail

// The closest plane or sphere hit in (t_min, h.t), into h. Planes and spheres are tested in
// the same order by every ISA; triangles, whose order depends on the tree's width, break
// ties by index (and win ties against the others). Whether there are any is asked inline,
// so that a scene of meshes only makes no call per ray (the call found nothing, 30
// instructions a ray).
MLIB_INLINE void closest_plane_or_sphere(const Accel& acc, const Ray& ray, float t_min, Hit& h) {
  if (has_planes_or_spheres(acc)) detail::closest_of_planes_and_spheres(acc, ray, t_min, h);
}

// The closest hit in (t_min, t_max) over planes, spheres and triangles; t = inf and
// prim = kNoHit when there is none.
//
// Always inlined into its caller's loop. GCC 12 kept the watertight instance out of line
// (the fast one it inlined) and returned its Hit by assembling it on the stack with 4- and
// 8-byte stores, then reading it back as two 8-byte halves for the registers: a load that
// spans two stores cannot take its data from the store buffer and waits for both to
// retire, once per ray. Inlined, the Hit stays in registers: bench_trace's watertight
// primary rays 9-21 % faster on the four bench-peer meshes (rt2 / Embree, old and new
// binaries alternated, three rounds, one thread), the fast test's rays unchanged (+-4 %).
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
  if (!h.found()) h.t = kInfinity;
  return h;
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

// Whether the spheres' tree is one leaf (or empty): then a packet tests its spheres in
// SIMD over rays, in the order of the one-ray walk; otherwise ray by ray (as it does rays
// whose w lanes are not +0, which the SIMD form does not carry).
inline bool spheres_in_one_leaf(const Accel& acc) {
  return acc.spheres.empty() || acc.sphere_bvh.nodes[0].is_leaf();
}

// closest_plane_or_sphere for each ray of `lanes` of a packet loaded into pr (hits[l].t is
// the bound on entry, as t_bound[l]), bit for bit, kRayLanes rays at a time; t_bound[l]
// (64-byte aligned, every lane) becomes hits[l].t, 0 outside `lanes`, written a vector at
// a time (read back a vector at a time by the triangles' walk).
inline void closest_plane_or_sphere_packet(const Accel& acc, const PacketRays<kWidth>& pr,
                                           PacketMask lanes, float t_min, Hit* hits,
                                           float* t_bound) {
  using V = mlib::vfloat<kRayLanes>;
  if (!has_planes_or_spheres(acc)) {
    for (int c = 0; c < kPacketSize; c += kRayLanes)
      select(V::bool_type::from_bits(lanes >> c & ((1u << kRayLanes) - 1)), V::load(t_bound + c),
             V::broadcast(0.0f))
          .store(t_bound + c);
    return;
  }
  if (!spheres_in_one_leaf(acc) || !pr.w_zero) {
    for (int l = 0; l < kPacketSize; ++l) {
      if (lanes >> l & 1) closest_plane_or_sphere(acc, pr.ray(l), t_min, hits[l]);
      t_bound[l] = lanes >> l & 1 ? hits[l].t : 0.0f;
    }
    return;
  }
  const V t_min_v = V::broadcast(t_min);
  const std::uint32_t first_sphere = acc.spheres.empty() ? 0 : acc.sphere_bvh.nodes[0].offset;
  const std::uint32_t spheres = acc.spheres.empty() ? 0 : acc.sphere_bvh.nodes[0].count;
  for (int c = 0; c < kPacketSize; c += kRayLanes) {
    const unsigned chunk = lanes >> c & ((1u << kRayLanes) - 1);
    V t_best = select(V::bool_type::from_bits(chunk), V::load(t_bound + c), V::broadcast(0.0f));
    if (!chunk) {
      t_best.store(t_bound + c);
      continue;
    }
    const RayLanes<V> r = ray_lanes(pr, c);
    alignas(64) float best[kRayLanes];
    for (std::uint32_t i = 0; i < acc.planes.size(); ++i) {
      const V t = plane_t(acc.planes[i], r);
      const auto hit = (t > t_min_v) & (t < t_best);
      t_best = select(hit, t, t_best);
      for (unsigned m = mlib::bits(hit) & chunk; m; m &= m - 1)
        hits[c + std::countr_zero(m)].prim = kPlaneTag | i;
    }
    for (std::uint32_t i = first_sphere; i < first_sphere + spheres; ++i) {
      const Sphere& sp = acc.spheres[i];
      const SphereRoots<V> roots = sphere_roots(sp, r);
      const auto near_in = (roots.lo > t_min_v) & (roots.lo < t_best);
      const auto far_in = (roots.hi > t_min_v) & (roots.hi < t_best);
      const auto hit = near_in | far_in;
      const unsigned m_hit = mlib::bits(hit) & roots.real & ~roots.doubled & chunk;
      const unsigned m_doubled = roots.doubled & chunk;
      if (!(m_hit | m_doubled)) continue;
      t_best = select(V::bool_type::from_bits(m_hit), select(near_in, roots.lo, roots.hi), t_best);
      for (unsigned m = m_hit; m; m &= m - 1) hits[c + std::countr_zero(m)].prim = kSphereTag | i;
      if (!m_doubled) continue;
      t_best.store(best);
      for (unsigned m = m_doubled; m; m &= m - 1) {  // the one-ray test's double branch
        const int l = std::countr_zero(m);
        float t1;
        if (intersect(sp, pr.ray(c + l), t_min, best[l], t1)) {
          best[l] = t1;
          hits[c + l].prim = kSphereTag | i;
        }
      }
      t_best = V::load(best);
    }
    t_best.store(t_bound + c);
    for (unsigned m = chunk; m; m &= m - 1) hits[c + std::countr_zero(m)].t = t_bound[c + std::countr_zero(m)];
  }
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

// closest_hit for each ray of a packet loaded into pr: hits[l] = closest_hit(acc, ray l,
// t_min, t_max[l]) for the lanes l of `lanes` (bit for bit the same; `finite`: those
// without a NaN coordinate, load_finite's answer), planes and spheres tested kRayLanes rays
// at a time, the triangles walked as one packet when the rays allow it
// (packet_traverse.h). t_max holds kPacketSize floats (all read; those outside `lanes` are
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
  PacketRays<kWidth> pr;
  const PacketMask finite =
      load_finite(pr, lanes, [rays](PacketRays<kWidth>& p, PacketMask m) { return p.load(rays, m); });
  alignas(64) float bound[kPacketSize];
  lane_bounds(lanes, t_max, bound);
  closest_hit_loaded<Watertight>(acc, pr, lanes, finite, t_min, bound, hits, counts);
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

namespace detail {
// plane_or_sphere_in_the_way's tests, for a scene that has planes or spheres.
inline bool plane_or_sphere_blocks(const Accel& acc, const Ray& ray, float t_min, float t_max) {
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
  return hit;
}
}  // namespace detail

// Whether a plane or a sphere (every surface opaque) lies on `ray` in (t_min, t_max); as
// closest_plane_or_sphere, whether there are any is asked inline.
MLIB_INLINE bool plane_or_sphere_in_the_way(const Accel& acc, const Ray& ray, float t_min,
                                            float t_max) {
  return has_planes_or_spheres(acc) && detail::plane_or_sphere_blocks(acc, ray, t_min, t_max);
}

// Whether anything at all (every surface opaque) lies on `ray` in (t_min, t_max).
// Always inlined into its caller's loop, as closest_hit: GCC 12 kept the watertight instance
// out of line, a call with the triangle test built in its frame for every ray.
template <bool Watertight>
MLIB_INLINE bool occluded(const Accel& acc, const Ray& ray, float t_min, float t_max,
                          TraversalCounts* counts = nullptr) {
  if (has_nan(ray)) return false;
  if (plane_or_sphere_in_the_way(acc, ray, t_min, t_max)) return true;
  return any_triangle<kWidth>(acc.wide<kWidth>(), acc.blocks.data(), ray, TriangleTest<Watertight>(ray),
                              t_min, t_max, [](std::uint32_t, float) { return true; }, counts);
}

// The rays of a packet (lanes of `lanes`) that something opaque blocks, as occluded says
// for each: the triangles walked as one packet when the rays allow it.
template <bool Watertight>
inline PacketMask occluded_packet(const Accel& acc, const Ray* rays, PacketMask lanes,
                                  float t_min, const float* t_max,
                                  TraversalCounts* counts = nullptr) {
  PacketRays<kWidth> pr;  // the frustum bounds the finite rays (a superset of the open ones)
  PacketMask open =
      load_finite(pr, lanes, [rays](PacketRays<kWidth>& p, PacketMask m) { return p.load(rays, m); });
  PacketMask blocked = 0;
  alignas(64) float bound[kPacketSize];
  lane_bounds(lanes, t_max, bound);
  for (PacketMask m = open; m; m &= m - 1) {
    const int l = std::countr_zero(m);
    if (plane_or_sphere_in_the_way(acc, rays[l], t_min, t_max[l])) blocked |= 1u << l;
  }
  open &= ~blocked;
  const WideBvh<kWidth>& bvh = acc.wide<kWidth>();
  if (!open || bvh.root == kNoChild) return blocked;
  const PacketMask walked =
      walk_as_packets(pr, open, [&](const PacketRays<kWidth>& p, PacketMask group) {
        const PacketTestFor<Watertight> pt(p, group);
        blocked |= any_triangle_packet<kWidth>(
            bvh, acc.blocks.data(), p, pt.test, group, t_min, bound,
            [](int, std::uint32_t, float) { return true; }, counts);
      });
  for (PacketMask m = open & ~walked; m; m &= m - 1) {
    const int l = std::countr_zero(m);
    if (any_triangle<kWidth>(bvh, acc.blocks.data(), rays[l], TriangleTest<Watertight>(rays[l]),
                             t_min, t_max[l], [](std::uint32_t, float) { return true; }, counts))
      blocked |= 1u << l;
  }
  return blocked;
}

// The transparencies Kt of the surfaces a shadow ray crosses, multiplied in an order that
// does not depend on the order they are found in, so that every ISA, BVH width and walk
// (one ray or a packet) gives the same value: each distinct Kt is kept with how many times
// it was crossed, and the product runs over the values in ascending order, each as many
// times as it was crossed (for up to 16 crossings, the product of the sorted factors).
class Crossings {
 public:
  // Adds a crossing of a surface of transparency k; returns true when no light can pass
  // any more (k = 0: opaque).
  bool cross(float k) {
    if (k == 0.0f) return true;
    for (int i = 0; i < distinct_; ++i)
      if (values_[i] == k) {
        ++counts_[i];
        return false;
      }
    if (distinct_ < kDistinct) {
      values_[distinct_] = k;
      counts_[distinct_++] = 1;
    } else {
      overflow_ *= k;
    }
    return false;
  }
  // The product of the factors (when cross never returned true).
  float transmittance() {
    for (int i = 1; i < distinct_; ++i)  // ascending (insertion sort: few values)
      for (int j = i; j > 0 && values_[j] < values_[j - 1]; --j) {
        std::swap(values_[j], values_[j - 1]);
        std::swap(counts_[j], counts_[j - 1]);
      }
    float tr = 1.0f;
    for (int i = 0; i < distinct_; ++i)
      for (std::uint32_t n = 0; n < counts_[i]; ++n) tr *= values_[i];
    return tr * overflow_;
  }

 private:
  static constexpr int kDistinct = 16;
  float values_[kDistinct];
  std::uint32_t counts_[kDistinct];
  int distinct_ = 0;
  // Beyond 16 distinct transparencies on one ray (materials of 17 different Kt crossed):
  // in found order, the one case where the walk's order shows in the last bits.
  float overflow_ = 1.0f;
};

// The crossings of planes and spheres on (t_min, t_max) of `ray`; returns true when one is
// opaque.
inline bool cross_planes_and_spheres(const Accel& acc, const std::vector<Material>& materials,
                                     const Ray& ray, float t_min, float t_max, Crossings& c) {
  for (std::uint32_t i = 0; i < acc.planes.size(); ++i) {
    float t;
    if (intersect(acc.planes[i], ray, t_min, t_max, t) &&
        c.cross(materials[acc.plane_materials[i]].transparency))
      return true;
  }
  float t_far = t_max;
  bool blocked = false;
  sphere_leaves<true>(acc, ray, t_min, t_far,
                      [&](std::uint32_t first, std::uint32_t count, float&) {
                        for (std::uint32_t i = first; i < first + count && !blocked; ++i) {
                          float t, t2;
                          if (!intersect(acc.spheres[i], ray, t_min, t_max, t)) continue;
                          const float k = materials[acc.sphere_materials[i]].transparency;
                          blocked = c.cross(k);
                          // The far side of a sphere is a second crossing.
                          if (!blocked && intersect(acc.spheres[i], ray, t, t_max, t2))
                            blocked = c.cross(k);
                        }
                        return blocked;
                      });
  return blocked;
}

// How much light passes along the segment (t_min, t_max) of `ray`: 1 when nothing is in
// the way, 0 when an opaque surface is, and the product of the transparencies Kt of every
// surface crossed otherwise (each crossing counts once: a glass sphere crossed through
// attenuates twice, as a closed glass mesh does).
template <bool Watertight>
inline float transmittance(const Accel& acc, const std::vector<Material>& materials,
                           const Ray& ray, float t_min, float t_max,
                           TraversalCounts* counts = nullptr) {
  if (has_nan(ray)) return 1.0f;
  Crossings c;
  if (cross_planes_and_spheres(acc, materials, ray, t_min, t_max, c)) return 0.0f;
  if (any_triangle<kWidth>(acc.wide<kWidth>(), acc.blocks.data(), ray, TriangleTest<Watertight>(ray),
                           t_min, t_max,
                           [&](std::uint32_t prim, float) {
                             return c.cross(materials[acc.tri_materials[prim]].transparency);
                           },
                           counts))
    return 0.0f;
  return c.transmittance();
}

// cross_planes_and_spheres for each ray of `lanes` of a packet loaded into pr, N rays at a
// time, each ray's crossings in the one-ray order; returns the rays an opaque one blocks.
inline PacketMask cross_planes_and_spheres_packet(const Accel& acc,
                                                  const std::vector<Material>& materials,
                                                  const PacketRays<kWidth>& pr, PacketMask lanes,
                                                  float t_min, const float* t_max, Crossings* c) {
  PacketMask blocked = 0;
  if (acc.planes.empty() && acc.spheres.empty()) return blocked;
  if (!spheres_in_one_leaf(acc) || !pr.w_zero) {
    for (PacketMask m = lanes; m; m &= m - 1) {
      const int l = std::countr_zero(m);
      if (cross_planes_and_spheres(acc, materials, pr.ray(l), t_min, t_max[l], c[l]))
        blocked |= PacketMask(1) << l;
    }
    return blocked;
  }
  using V = mlib::vfloat<kRayLanes>;
  const V t_min_v = V::broadcast(t_min);
  const std::uint32_t first_sphere = acc.spheres.empty() ? 0 : acc.sphere_bvh.nodes[0].offset;
  const std::uint32_t spheres = acc.spheres.empty() ? 0 : acc.sphere_bvh.nodes[0].count;
  for (int k = 0; k < kPacketSize; k += kRayLanes) {
    unsigned open = lanes >> k & ((1u << kRayLanes) - 1);
    if (!open) continue;
    const RayLanes<V> r = ray_lanes(pr, k);
    const V t_max_v = select(V::bool_type::from_bits(lanes >> k & ((1u << kRayLanes) - 1)),
                             V::loadu(t_max + k), V::broadcast(0.0f));
    const auto cross = [&](int l, float kt) {  // lane l of this chunk crosses a surface
      if (c[k + l].cross(kt)) open &= ~(1u << l);
    };
    for (std::uint32_t i = 0; i < acc.planes.size() && open; ++i) {
      const unsigned m = inside(plane_t(acc.planes[i], r), t_min_v, t_max_v) & open;
      if (!m) continue;
      const float kt = materials[acc.plane_materials[i]].transparency;
      for (unsigned b = m; b; b &= b - 1) cross(std::countr_zero(b), kt);
    }
    for (std::uint32_t i = first_sphere; i < first_sphere + spheres && open; ++i) {
      const Sphere& sp = acc.spheres[i];
      const SphereRoots<V> roots = sphere_roots(sp, r);
      const unsigned usable = roots.real & ~roots.doubled & open;
      const unsigned near_in = inside(roots.lo, t_min_v, t_max_v) & usable;
      const unsigned far_in = inside(roots.hi, t_min_v, t_max_v) & usable;
      const unsigned doubled = roots.doubled & open;
      if (!(near_in | far_in | doubled)) continue;
      const float kt = materials[acc.sphere_materials[i]].transparency;
      // The one-ray order: the first root in range, then the far root when it lies beyond
      // it (and before t_max).
      const unsigned far_beyond = mlib::bits(roots.hi > roots.lo) & far_in & near_in;
      for (unsigned b = near_in | far_in; b; b &= b - 1) {
        const int l = std::countr_zero(b);
        cross(l, kt);
        if (far_beyond >> l & 1 && open >> l & 1) cross(l, kt);
      }
      for (unsigned b = doubled; b; b &= b - 1) {  // the one-ray test's double branch
        const int l = std::countr_zero(b);
        float t, t2;
        const Ray ray = pr.ray(k + l);
        if (!intersect(sp, ray, t_min, t_max[k + l], t)) continue;
        cross(l, kt);
        if (open >> l & 1 && intersect(sp, ray, t, t_max[k + l], t2)) cross(l, kt);
      }
    }
    blocked |= PacketMask((lanes >> k & ((1u << kRayLanes) - 1)) & ~open) << k;
  }
  return blocked;
}

// transmittance for each ray of a packet loaded into pr: passed[l] for the lanes l of
// `lanes` (`finite`: load_finite's answer), bit for bit what transmittance gives, planes and
// spheres tested kRayLanes rays at a time, the triangles walked as one packet when the
// rays allow it. t_max holds kPacketSize floats (all read, those outside `lanes` unused).
template <bool Watertight>
inline void transmittance_loaded(const Accel& acc, const std::vector<Material>& materials,
                                 PacketRays<kWidth>& pr, PacketMask lanes, PacketMask finite,
                                 float t_min, const float* t_max, float* passed,
                                 TraversalCounts* counts) {
  Crossings c[kPacketSize];
  for (PacketMask m = lanes & ~finite; m; m &= m - 1) passed[std::countr_zero(m)] = 1.0f;
  if (!finite) return;
  PacketMask blocked = cross_planes_and_spheres_packet(acc, materials, pr, finite, t_min, t_max, c);
  const PacketMask open = finite & ~blocked;
  const WideBvh<kWidth>& bvh = acc.wide<kWidth>();
  const auto cross_triangle = [&](int l, std::uint32_t prim) {
    return c[l].cross(materials[acc.tri_materials[prim]].transparency);
  };
  if (open && bvh.root != kNoChild) {
    const PacketMask walked =
        walk_as_packets(pr, open, [&](const PacketRays<kWidth>& p, PacketMask group) {
          const PacketTestFor<Watertight> pt(p, group);
          blocked |= any_triangle_packet<kWidth>(
              bvh, acc.blocks.data(), p, pt.test, group, t_min, t_max,
              [&](int l, std::uint32_t prim, float) { return cross_triangle(l, prim); }, counts);
        });
    for (PacketMask m = open & ~walked; m; m &= m - 1) {
      const int l = std::countr_zero(m);
      const Ray ray = pr.ray(l);
      if (any_triangle<kWidth>(bvh, acc.blocks.data(), ray, TriangleTest<Watertight>(ray),
                               t_min, t_max[l],
                               [&](std::uint32_t prim, float) { return cross_triangle(l, prim); },
                               counts))
        blocked |= PacketMask(1) << l;
    }
  }
  for (PacketMask m = finite; m; m &= m - 1) {
    const int l = std::countr_zero(m);
    passed[l] = blocked >> l & 1 ? 0.0f : c[l].transmittance();
  }
}

// transmittance_loaded for rays[l], l in `lanes`.
template <bool Watertight>
inline void transmittance_packet(const Accel& acc, const std::vector<Material>& materials,
                                 const Ray* rays, PacketMask lanes, float t_min,
                                 const float* t_max, float* passed,
                                 TraversalCounts* counts = nullptr) {
  PacketRays<kWidth> pr;
  const PacketMask finite =
      load_finite(pr, lanes, [rays](PacketRays<kWidth>& p, PacketMask m) { return p.load(rays, m); });
  alignas(64) float bound[kPacketSize];
  lane_bounds(lanes, t_max, bound);
  transmittance_loaded<Watertight>(acc, materials, pr, lanes, finite, t_min, bound, passed, counts);
}

// transmittance_loaded for the rays first + l of columns, l in `lanes` (the columns are
// read at first ... first + kPacketSize - 1, and t_max's kPacketSize floats).
template <bool Watertight>
inline void transmittance_packet(const Accel& acc, const std::vector<Material>& materials,
                                 const RayColumns& rays, std::size_t first, PacketMask lanes,
                                 float t_min, const float* t_max, float* passed,
                                 TraversalCounts* counts = nullptr) {
  PacketRays<kWidth> pr;
  const PacketMask finite = load_finite(
      pr, lanes, [&rays, first](PacketRays<kWidth>& p, PacketMask m) { return p.load(rays, first, m); });
  transmittance_loaded<Watertight>(acc, materials, pr, lanes, finite, t_min, t_max, passed, counts);
}

}  // namespace rt2::RT2_ISA
