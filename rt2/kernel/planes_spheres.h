// rt2/kernel/planes_spheres.h — the planes' and spheres' part of each query, for one ray and
// for a packet: the closest of them, and the surfaces crossed on a segment.
//
// Planes are unbounded and few: a loop. Spheres keep their binary tree (bvh/traverse.h), and
// a tree of one leaf (the usual scene) is tested without the walk. A packet tests them
// kRayLanes rays at a time, bit for bit as the one-ray tests, where the spheres are one leaf
// and the rays' w lanes are +0; otherwise ray by ray. Every ISA tests them in the same order.
#pragma once

#include <bit>
#include <cstdint>

#include "rt2/kernel/kernel.h"

#include "rt2/bvh/accel.h"
#include "rt2/bvh/traverse.h"
#include "rt2/kernel/query_rays.h"

namespace rt2::RT2_ISA {

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

// The closest plane or sphere hit in (t_min, h.t), into h. Planes and spheres are tested in
// the same order by every ISA; triangles, whose order depends on the tree's width, break
// ties by index (and win ties against the others). Whether there are any is asked inline,
// so that a scene of meshes only makes no call per ray.
MLIB_INLINE void closest_plane_or_sphere(const Accel& acc, const Ray& ray, float t_min, Hit& h) {
  if (has_planes_or_spheres(acc)) closest_of_planes_and_spheres(acc, ray, t_min, h);
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

// Calls cross(prim) for the planes and spheres on (t_min, t_max) of `ray`, a sphere twice
// when the segment passes through it (its near and far side), until cross returns true;
// returns whether it did. Planes first, then spheres in their tree's order.
template <class Cross>
inline bool cross_planes_and_spheres(const Accel& acc, const Ray& ray, float t_min, float t_max,
                                     Cross&& cross) {
  for (std::uint32_t i = 0; i < acc.planes.size(); ++i) {
    float t;
    if (intersect(acc.planes[i], ray, t_min, t_max, t) && cross(kPlaneTag | i)) return true;
  }
  float t_far = t_max;
  bool blocked = false;
  sphere_leaves<true>(acc, ray, t_min, t_far,
                      [&](std::uint32_t first, std::uint32_t count, float&) {
                        for (std::uint32_t i = first; i < first + count && !blocked; ++i) {
                          float t, t2;
                          if (!intersect(acc.spheres[i], ray, t_min, t_max, t)) continue;
                          blocked = cross(kSphereTag | i);
                          if (!blocked && intersect(acc.spheres[i], ray, t, t_max, t2))
                            blocked = cross(kSphereTag | i);
                        }
                        return blocked;
                      });
  return blocked;
}

// cross_planes_and_spheres for each ray of `lanes` of a packet loaded into pr, kRayLanes rays
// at a time, each ray's crossings in the one-ray order, cross(l, prim) for lane l; returns
// the lanes for which cross returned true.
template <class Cross>
inline PacketMask cross_planes_and_spheres_packet(const Accel& acc, const PacketRays<kWidth>& pr,
                                                  PacketMask lanes, float t_min,
                                                  const float* t_max, Cross&& cross) {
  PacketMask blocked = 0;
  if (!has_planes_or_spheres(acc)) return blocked;
  if (!spheres_in_one_leaf(acc) || !pr.w_zero) {
    for (PacketMask m = lanes; m; m &= m - 1) {
      const int l = std::countr_zero(m);
      if (cross_planes_and_spheres(acc, pr.ray(l), t_min, t_max[l],
                                   [&](PrimRef prim) { return cross(l, prim); }))
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
    const auto cross_lane = [&](int l, PrimRef prim) {  // lane l of this chunk crosses prim
      if (cross(k + l, prim)) open &= ~(1u << l);
    };
    for (std::uint32_t i = 0; i < acc.planes.size() && open; ++i) {
      const unsigned m = inside(plane_t(acc.planes[i], r), t_min_v, t_max_v) & open;
      for (unsigned b = m; b; b &= b - 1) cross_lane(std::countr_zero(b), kPlaneTag | i);
    }
    for (std::uint32_t i = first_sphere; i < first_sphere + spheres && open; ++i) {
      const Sphere& sp = acc.spheres[i];
      const SphereRoots<V> roots = sphere_roots(sp, r);
      const unsigned usable = roots.real & ~roots.doubled & open;
      const unsigned near_in = inside(roots.lo, t_min_v, t_max_v) & usable;
      const unsigned far_in = inside(roots.hi, t_min_v, t_max_v) & usable;
      const unsigned doubled = roots.doubled & open;
      if (!(near_in | far_in | doubled)) continue;
      // The one-ray order: the first root in range, then the far root when it lies beyond
      // it (and before t_max).
      const unsigned far_beyond = mlib::bits(roots.hi > roots.lo) & far_in & near_in;
      for (unsigned b = near_in | far_in; b; b &= b - 1) {
        const int l = std::countr_zero(b);
        cross_lane(l, kSphereTag | i);
        if (far_beyond >> l & 1 && open >> l & 1) cross_lane(l, kSphereTag | i);
      }
      for (unsigned b = doubled; b; b &= b - 1) {  // the one-ray test's double branch
        const int l = std::countr_zero(b);
        float t, t2;
        const Ray ray = pr.ray(k + l);
        if (!intersect(sp, ray, t_min, t_max[k + l], t)) continue;
        cross_lane(l, kSphereTag | i);
        if (open >> l & 1 && intersect(sp, ray, t, t_max[k + l], t2)) cross_lane(l, kSphereTag | i);
      }
    }
    blocked |= PacketMask((lanes >> k & ((1u << kRayLanes) - 1)) & ~open) << k;
  }
  return blocked;
}

}  // namespace rt2::RT2_ISA
