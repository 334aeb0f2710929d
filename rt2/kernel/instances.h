// rt2/kernel/instances.h — the top level of the two-level tree (rt2/bvh/accel.h): a ray
// walks the binary tree over the instances' world boxes and, in each instance it enters,
// its mesh's wide tree in the mesh's coordinates, with the same walks as the world's
// triangles. The ray is transformed, not renormalised: t stays the world's distance.
#pragma once

#include <bit>
#include <cstdint>
#include <utility>

#include "rt2/kernel/kernel.h"

#include "rt2/bvh/accel.h"
#include "rt2/bvh/traverse.h"
#include "rt2/kernel/packet_traverse.h"
#include "rt2/kernel/query_rays.h"
#include "rt2/kernel/wide_traverse.h"

namespace rt2::RT2_ISA {

// `ray` in instance `in`'s coordinates: as it is for the identity, else transformed.
MLIB_INLINE Ray ray_in(const TracedInstance& in, const Ray& ray) {
  if (in.identity) return ray;
  return Ray(in.to_object.point(ray.org), in.to_object.direction(ray.dir));
}

// Whether a ray made by ray_in stays in float range (else it meets nothing in the instance).
MLIB_INLINE bool finite_ray(const Ray& r) {
  const vec4 zero(0.0f, 0.0f, 0.0f, 0.0f);
  return (r.org - r.org) == zero && (r.dir - r.dir) == zero;
}

// The closest triangle of any instance nearer than h.t into h, with h.instance naming the
// instance. Ties go to the smaller (triangle, instance) (tie_prior), so the order in which
// instances are walked does not matter: a packet's walk finds the same hits.
template <bool Watertight>
MLIB_INLINE void closest_instanced(const Accel& acc, const Ray& ray, float t_min, Hit& h,
                                   TraversalCounts* counts) {
  if (acc.instances.empty()) return;
  const std::uint32_t* order = acc.instance_bvh.order.data();
  const auto leaf = [&](std::uint32_t first, std::uint32_t count, float& t_max) {
    for (std::uint32_t k = first; k < first + count; ++k) {
      const std::uint32_t i = order[k];
      const TracedInstance& in = acc.instances[i];
      const Ray local = ray_in(in, ray);
      if (!finite_ray(local)) continue;
      if (closest_triangle<kWidth>(acc.mesh_tree<kWidth>(in.mesh), acc.blocks.data(), local,
                                   TriangleTest<Watertight>(local), t_min, h, counts, i))
        t_max = h.t;
    }
    return false;
  };
  float t_far = h.t;
  // A top level of one leaf: its instances' trees test their own boxes (may_enter).
  const BvhNode& root = acc.instance_bvh.nodes[0];
  if (root.is_leaf())
    leaf(root.offset, root.count, t_far);
  else
    traverse<false>(acc.instance_bvh, RayPre(ray), t_min, t_far, leaf);
}

// Calls cross(prim, instance) for the instances' triangles on (t_min, t_max) of `ray`, in
// no particular order, until it returns true; returns whether it did.
template <bool Watertight, class Cross>
MLIB_INLINE bool any_instanced(const Accel& acc, const Ray& ray, float t_min, float t_max,
                               Cross&& cross, TraversalCounts* counts) {
  if (acc.instances.empty()) return false;
  bool stopped = false;
  const std::uint32_t* order = acc.instance_bvh.order.data();
  const auto leaf = [&](std::uint32_t first, std::uint32_t count, float&) {
    for (std::uint32_t k = first; k < first + count && !stopped; ++k) {
      const std::uint32_t i = order[k];
      const TracedInstance& in = acc.instances[i];
      const Ray local = ray_in(in, ray);
      if (!finite_ray(local)) continue;
      stopped = any_triangle<kWidth>(
          acc.mesh_tree<kWidth>(in.mesh), acc.blocks.data(), local,
          TriangleTest<Watertight>(local), t_min, t_max,
          [&](std::uint32_t prim, float) { return cross(PrimRef(prim), i); }, counts);
    }
    return stopped;
  };
  float t_far = t_max;
  const BvhNode& root = acc.instance_bvh.nodes[0];
  if (root.is_leaf())
    leaf(root.offset, root.count, t_far);
  else
    traverse<true>(acc.instance_bvh, RayPre(ray), t_min, t_far, leaf);
  return stopped;
}

// The lanes of `lanes` of pr whose rays enter box `n` within (t_min, t_max[l]), and in
// `*nearest` (when given) the smallest of their entry distances: node_entry's arithmetic
// (so the same lanes as each ray's own test, t_min not NaN), kRayLanes rays at a time;
// `inv` holds the reciprocals of the rays' directions, as RayPre computes them.
MLIB_INLINE PacketMask box_lanes(const BvhNode& n, const PacketRays<kWidth>& pr,
                                 const float (*inv)[kPacketSize], PacketMask lanes, float t_min,
                                 const float* t_max, float* nearest) {
  using R = mlib::vfloat<kRayLanes>;
  const R minus_inf = R::broadcast(-kInfinity), inf = R::broadcast(kInfinity);
  R lo[3], hi[3];
  for (int a = 0; a < 3; ++a) lo[a] = R::broadcast(n.lo[a]), hi[a] = R::broadcast(n.hi[a]);
  PacketMask in = 0;
  R entry_min = inf;
  for (int c = 0; c < kPacketSize; c += kRayLanes) {
    if (!(lanes >> c & PacketRays<kWidth>::kChunk)) continue;
    R near = R::broadcast(t_min), far = inf;
    for (int a = 0; a < 3; ++a) {
      const R o = R::load(pr.org[a] + c), i = R::load(inv[a] + c);
      const R t0 = (lo[a] - o) * i, t1 = (hi[a] - o) * i;
      near = max(near, min(max(t0, minus_inf), max(t1, minus_inf)));
      far = min(far, max(min(t0, inf), min(t1, inf)));
    }
    far = min(far, R::loadu(t_max + c)) * R::broadcast(kSlabPad);
    // node_entry answers its entry distance, kInfinity for a miss: an entry at +inf is one
    const auto active = R::bool_type::from_bits(unsigned(lanes >> c & PacketRays<kWidth>::kChunk));
    const auto enters = (near <= far) & (near < inf) & active;
    in |= PacketMask(mlib::bits(enters)) << c;
    if (nearest) entry_min = min(entry_min, select(enters, near, inf));
  }
  if (nearest) {
    alignas(64) float x[kRayLanes];
    mlib::reduce_min(entry_min).store(x);
    *nearest = x[0];
  }
  return in;
}

// Calls visit(i, entering) for each instance i whose box some ray of `lanes` (of pr) enters
// within (t_min, t_max), `entering` those rays; every instance with all of `lanes` when
// the top level is one leaf (the instances' trees test their own boxes). t_max may shrink
// between visits (each node's children are tested against it). Nearer first: of two
// children, the one with the smaller entry distance is walked first.
template <bool NearerFirst, class Visit>
inline void instances_entered(const Accel& acc, const PacketRays<kWidth>& pr, PacketMask lanes,
                              float t_min, const float* t_max, Visit&& visit) {
  using R = mlib::vfloat<kRayLanes>;
  const BvhNode* nodes = acc.instance_bvh.nodes.data();
  const std::uint32_t* order = acc.instance_bvh.order.data();
  if (nodes[0].is_leaf()) {
    for (std::uint32_t k = nodes[0].offset; k < nodes[0].offset + nodes[0].count; ++k)
      visit(order[k], lanes);
    return;
  }
  alignas(64) float inv[3][kPacketSize];
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < kPacketSize; c += kRayLanes)
      (R::broadcast(1.0f) / R::load(pr.dir[a] + c)).store(inv[a] + c);
  struct Entry {
    std::uint32_t node;
    PacketMask lanes;
  };
  Entry stack[kMaxBvhDepth + 2];
  int sp = 0;
  const PacketMask root = box_lanes(nodes[0], pr, inv, lanes, t_min, t_max, nullptr);
  if (root) stack[sp++] = {0, root};
  while (sp > 0) {
    const Entry e = stack[--sp];
    const BvhNode& n = nodes[e.node];
    if (n.is_leaf()) {
      for (std::uint32_t k = n.offset; k < n.offset + n.count; ++k) visit(order[k], e.lanes);
      continue;
    }
    std::uint32_t a = e.node + 1, b = n.offset;
    float ta = 0.0f, tb = 0.0f;
    PacketMask in_a = box_lanes(nodes[a], pr, inv, e.lanes, t_min, t_max, NearerFirst ? &ta : nullptr);
    PacketMask in_b = box_lanes(nodes[b], pr, inv, e.lanes, t_min, t_max, NearerFirst ? &tb : nullptr);
    if (NearerFirst && tb < ta) {
      std::swap(a, b);
      std::swap(in_a, in_b);
    }
    if (in_b) stack[sp++] = {b, in_b};
    if (in_a) stack[sp++] = {a, in_a};  // popped next
  }
}

// The rays of `lanes` of pr in instance `in`'s coordinates, loaded into lp, kRayLanes at a
// time in the operations and order of ray_in (so each ray is the bits ray_in makes); returns the lanes whose rays have no infinite or NaN coordinate.
inline PacketMask load_entered(const TracedInstance& in, const PacketRays<kWidth>& pr,
                               PacketMask lanes, PacketRays<kWidth>& lp) {
  using R = mlib::vfloat<kRayLanes>;
  alignas(64) float org[4][kPacketSize], dir[4][kPacketSize];
  const R zero = R::broadcast(0.0f);
  PacketMask finite = 0;
  for (int g = 0; g < kPacketSize; g += kRayLanes) {
    R o[3], d[3];
    for (int a = 0; a < 3; ++a) o[a] = R::load(pr.org[a] + g), d[a] = R::load(pr.dir[a] + g);
    const vec4* c = in.to_object.c;
    auto ok = R::bool_type::from_bits(unsigned(PacketRays<kWidth>::kChunk));
    for (int a = 0; a < 3; ++a) {
      const R oa = in.identity ? o[a]
                               : ((R::broadcast(c[0][a]) * o[0] + R::broadcast(c[1][a]) * o[1]) +
                                  R::broadcast(c[2][a]) * o[2]) +
                                     R::broadcast(c[3][a]);
      const R da = in.identity ? d[a]
                               : ((R::broadcast(c[0][a]) * d[0] + R::broadcast(c[1][a]) * d[1]) +
                                  R::broadcast(c[2][a]) * d[2]) +
                                     zero;
      oa.store(org[a] + g);
      da.store(dir[a] + g);
      ok = ok & (oa - oa == zero) & (da - da == zero);
    }
    (in.identity ? R::load(pr.org_w + g) : zero).store(org[3] + g);
    (in.identity ? R::load(pr.dir_w + g) : zero).store(dir[3] + g);
    finite |= PacketMask(mlib::bits(ok)) << g;
  }
  const RayColumns columns{{org[0], org[1], org[2], org[3]}, {dir[0], dir[1], dir[2], dir[3]}};
  const PacketMask entered = lanes & finite;
  if (!entered) return 0;
  return load_finite(lp, entered, [&columns](PacketRays<kWidth>& p, PacketMask m) {
    return p.load(columns, 0, m);
  });
}

// closest_instanced for each ray of `lanes` of a packet loaded into pr, bit for bit: the top
// level walked with the packet's lanes, each instance's tree by the packet walk where the
// rays entering it allow (packet_traverse.h), else ray by ray.
template <bool Watertight>
inline void closest_instanced_packet(const Accel& acc, const PacketRays<kWidth>& pr,
                                     PacketMask lanes, float t_min, Hit* hits,
                                     TraversalCounts* counts) {
  if (acc.instances.empty() || !lanes) return;
  if (std::popcount(lanes) < kMinPacketRays) {
    for (PacketMask m = lanes; m; m &= m - 1) {
      const int l = std::countr_zero(m);
      closest_instanced<Watertight>(acc, pr.ray(l), t_min, hits[l], counts);
    }
    return;
  }
  alignas(64) float t_bound[kPacketSize];
  for (int l = 0; l < kPacketSize; ++l) t_bound[l] = lanes >> l & 1 ? hits[l].t : 0.0f;
  instances_entered<true>(acc, pr, lanes, t_min, t_bound, [&](std::uint32_t i, PacketMask entering) {
    const TracedInstance& in = acc.instances[i];
    const WideBvh<kWidth>& tree = acc.mesh_tree<kWidth>(in.mesh);
    PacketRays<kWidth> lp;
    const PacketMask finite = load_entered(in, pr, entering, lp);
    PrimRef prior[kPacketSize], biased[kPacketSize];
    for (PacketMask m = finite; m; m &= m - 1) {
      const int l = std::countr_zero(m);
      prior[l] = hits[l].prim;
      biased[l] = hits[l].prim = tie_prior(hits[l], i);
    }
    const PacketMask walked =
        walk_as_packets(lp, finite, [&](const PacketRays<kWidth>& p, PacketMask group) {
          const PacketTestFor<Watertight> pt(p, group);
          closest_triangle_packet<kWidth>(tree, acc.blocks.data(), p, pt.test, group, t_min,
                                          t_bound, hits, counts);
        });
    for (PacketMask m = finite & ~walked; m; m &= m - 1) {
      const int l = std::countr_zero(m);
      const Ray ray = lp.ray(l);
      closest_triangle<kWidth>(tree, acc.blocks.data(), ray, TriangleTest<Watertight>(ray), t_min,
                               hits[l], counts);
    }
    for (PacketMask m = finite; m; m &= m - 1) {
      const int l = std::countr_zero(m);
      if (hits[l].t != t_bound[l] || hits[l].prim != biased[l])
        hits[l].instance = i;
      else
        hits[l].prim = prior[l];
      t_bound[l] = hits[l].t;
    }
  });
}

// any_instanced for each ray of `lanes` of a packet loaded into pr: cross(l, prim, instance)
// for lane l's triangles; returns the lanes for which it returned true.
template <bool Watertight, class Cross>
inline PacketMask any_instanced_packet(const Accel& acc, const PacketRays<kWidth>& pr,
                                       PacketMask lanes, float t_min, const float* t_max,
                                       Cross&& cross, TraversalCounts* counts) {
  if (acc.instances.empty() || !lanes) return 0;
  PacketMask blocked = 0;
  if (std::popcount(lanes) < kMinPacketRays) {
    for (PacketMask m = lanes; m; m &= m - 1) {
      const int l = std::countr_zero(m);
      if (any_instanced<Watertight>(
              acc, pr.ray(l), t_min, t_max[l],
              [&](PrimRef prim, std::uint32_t instance) { return cross(l, prim, instance); },
              counts))
        blocked |= PacketMask(1) << l;
    }
    return blocked;
  }
  instances_entered<false>(acc, pr, lanes, t_min, t_max, [&](std::uint32_t i, PacketMask entering) {
    entering &= ~blocked;
    if (!entering) return;
    const TracedInstance& in = acc.instances[i];
    const WideBvh<kWidth>& tree = acc.mesh_tree<kWidth>(in.mesh);
    if (tree.root == kNoChild) return;
    PacketRays<kWidth> lp;
    const PacketMask finite = load_entered(in, pr, entering, lp);
    const auto on_hit = [&](int l, std::uint32_t prim, float) { return cross(l, PrimRef(prim), i); };
    const PacketMask walked =
        walk_as_packets(lp, finite, [&](const PacketRays<kWidth>& p, PacketMask group) {
          const PacketTestFor<Watertight> pt(p, group);
          blocked |= any_triangle_packet<kWidth>(tree, acc.blocks.data(), p, pt.test, group,
                                                 t_min, t_max, on_hit, counts);
        });
    for (PacketMask m = finite & ~walked; m; m &= m - 1) {
      const int l = std::countr_zero(m);
      const Ray ray = lp.ray(l);
      if (any_triangle<kWidth>(tree, acc.blocks.data(), ray, TriangleTest<Watertight>(ray), t_min,
                               t_max[l],
                               [&](std::uint32_t prim, float t) { return on_hit(l, prim, t); },
                               counts))
        blocked |= PacketMask(1) << l;
    }
  });
  return blocked;
}

}  // namespace rt2::RT2_ISA
