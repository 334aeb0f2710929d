// rt2/kernel/packet_traverse.h — walking the wide BVH with a packet of up to 16 coherent
// rays (4 x 4 primary rays, or shadow rays towards one light): closest and any hit.
//
// Inner nodes are tested against the packet's frustum (interval arithmetic over the rays'
// origins and reciprocal directions; Boulos et al. 2007), one SIMD pass over a node's
// children for all rays; the rays must share their direction's signs. The frustum only
// filters: each child it passes is then tested ray by ray with each ray's own arithmetic,
// and leaves are tested only by the rays that entered them, so every ray finds the hit of
// its own walk (wide_traverse.h), bit for bit, and the packet never visits more nodes than
// its rays' walks together.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>

#include "rt2/kernel/kernel.h"

#include "rt2/kernel/triangle_packet_intersect.h"
#include "rt2/kernel/wide_traverse.h"

namespace rt2::RT2_ISA {

// Why the frustum never culls a box one of the rays enters. Per axis, with the ray's own
// rows, its entry distance is n = (b_near - o) * inv and its exit f = (b_far - o) * inv_far
// (inv_far = inv * kSlabPad, as in wide_traverse.h). Rounding is monotone, so over the
// packet n >= (b_near - O_near) * I_near where O_near is the origin bound that makes the
// difference smallest in magnitude and I_near the reciprocal of smallest magnitude, as long
// as that difference has the sign of a box in front; when it has not, the bound is negative
// and the entry is t_min's anyway (the node test takes the maximum with t_min >= 0).
// Likewise f <= (b_far - O_far) * I_far with the largest magnitudes, and a ray whose exit
// is negative fails its own test. Compared as integers (NodeRay<N, true>), as every ray's
// own test compares them, the packet enters a box whenever a ray does. The closest-hit walk
// visits children nearest first by the frustum's entry distance and drops a subtree that
// lies beyond every ray's hit.
// A packet's rays as the walk needs them: structure of arrays for SIMD over rays (the
// per-ray slab terms of NodeRay<N, true>), and the frustum that bounds them.
template <int N>
struct PacketRays {
  using V = mlib::vfloat<N>;            // a node's N children
  using R = mlib::vfloat<kRayLanes>;    // kRayLanes of the packet's rays
  static constexpr PacketMask kChunk = (PacketMask(1) << kRayLanes) - 1;

  alignas(64) float org[3][kPacketSize];
  alignas(64) float dir[3][kPacketSize];
  alignas(64) float org_w[kPacketSize], dir_w[kPacketSize];  // the w lanes (ray(l) gives them back)
  alignas(64) float inv_near[3][kPacketSize];
  alignas(64) float inv_far[3][kPacketSize];
  int near[3], far[3];  // box rows, shared by all rays
  // The frustum, per axis: (bounds[near] - o_near) * i_near is at most every ray's entry
  // distance, (bounds[far] - o_far) * i_far at least every exit (see above).
  V o_near[3], o_far[3], i_near[3], i_far[3];
  // Whether every loaded ray's w lanes are +0, as ray.h's invariant says (the structure of
  // arrays holds x, y, z only; code that emulates four-lane arithmetic relies on it).
  bool w_zero = true;

  // Loads rays[l] for the lanes l of `lanes` (at least one) into org and dir (and their w
  // lanes into org_w and dir_w), four rays at a
  // time (a transpose); returns those lanes whose ray has no NaN coordinate (w included,
  // as has_nan checks). Lanes without a ray take the first ray's values: their bits are
  // masked off later, and the frustum's bounds stay those of the rays. When a ray has a NaN,
  // load again with the returned lanes.
  PacketMask load(const Ray* rays, PacketMask lanes) {
    namespace simd = mlib::simd;
    const Ray* first = rays + std::countr_zero(lanes);
    PacketMask nan = 0;
    w_zero = true;
    for (int g = 0; g < kPacketSize; g += 4) {
      const Ray* r[4];
      for (int i = 0; i < 4; ++i) r[i] = lanes >> (g + i) & 1 ? rays + g + i : first;
      simd::f4 ox, oy, oz, ow, dx, dy, dz, dw;
      simd::transpose4(r[0]->org.m128(), r[1]->org.m128(), r[2]->org.m128(), r[3]->org.m128(),
                       ox, oy, oz, ow);
      simd::transpose4(r[0]->dir.m128(), r[1]->dir.m128(), r[2]->dir.m128(), r[3]->dir.m128(),
                       dx, dy, dz, dw);
      simd::store(org[0] + g, ox), simd::store(org[1] + g, oy), simd::store(org[2] + g, oz);
      simd::store(dir[0] + g, dx), simd::store(dir[1] + g, dy), simd::store(dir[2] + g, dz);
      simd::store(org_w + g, ow), simd::store(dir_w + g, dw);
      // NaN checked here, not reloaded from the arrays: a wide load of narrower stores
      // would wait for them to commit.
      const simd::f4 o_nan = simd::bit_or(simd::bit_or(simd::cmp_ne(ox, ox), simd::cmp_ne(oy, oy)),
                                          simd::bit_or(simd::cmp_ne(oz, oz), simd::cmp_ne(ow, ow)));
      const simd::f4 d_nan = simd::bit_or(simd::bit_or(simd::cmp_ne(dx, dx), simd::cmp_ne(dy, dy)),
                                          simd::bit_or(simd::cmp_ne(dz, dz), simd::cmp_ne(dw, dw)));
      nan |= PacketMask(simd::movemask(simd::bit_or(o_nan, d_nan))) << g;
      // +0 exactly: equal to 0, sign bit clear.
      const simd::f4 zero = simd::zero();
      w_zero = w_zero && simd::all(simd::cmp_eq(ow, zero)) && simd::movemask(ow) == 0 &&
               simd::all(simd::cmp_eq(dw, zero)) && simd::movemask(dw) == 0;
    }
    return lanes & ~nan;
  }

  // The same from columns: rays first + l for the lanes l of `lanes`, kRayLanes at a time
  // (the columns are read at first ... first + kPacketSize - 1 whatever the lanes: they
  // must be that long). Same lanes, values and answer as the load above.
  PacketMask load(const RayColumns& c, std::size_t first, PacketMask lanes) {
    const std::size_t f = first + std::size_t(std::countr_zero(lanes));
    const R zero = R::broadcast(0.0f), one = R::broadcast(1.0f);
    PacketMask nan = 0;
    bool w_plus_zero = true;
    for (int g = 0; g < kPacketSize; g += kRayLanes) {
      const unsigned chunk = lanes >> g & kChunk;
      const auto in = R::bool_type::from_bits(chunk);
      const auto column = [&](const float* col, float* out) {
        R v = R::loadu(col + first + std::size_t(g));
        if (chunk != kChunk) v = select(in, v, R::broadcast(col[f]));
        v.store(out + g);
        return v;
      };
      R o[4], d[4];
      for (int a = 0; a < 3; ++a) o[a] = column(c.org[a], org[a]), d[a] = column(c.dir[a], dir[a]);
      o[3] = column(c.org[3], org_w);
      d[3] = column(c.dir[3], dir_w);
      auto is_nan = (o[0] != o[0]) | (d[0] != d[0]);
      for (int a = 1; a < 4; ++a) is_nan = is_nan | (o[a] != o[a]) | (d[a] != d[a]);
      nan |= PacketMask(mlib::bits(is_nan)) << g;
      // +0 exactly: equal to 0, sign bit clear.
      w_plus_zero = w_plus_zero && mlib::bits((o[3] == zero) & (d[3] == zero)) == kChunk &&
                    mlib::bits((xor_sign(one, o[3]) < zero) | (xor_sign(one, d[3]) < zero)) == 0;
    }
    w_zero = w_plus_zero;
    return lanes & ~nan;
  }
  // The rays of `lanes` of another packet.
  PacketMask load(const PacketRays& from, PacketMask lanes) {
    return load(RayColumns{{from.org[0], from.org[1], from.org[2], from.org_w},
                           {from.dir[0], from.dir[1], from.dir[2], from.dir_w}},
                0, lanes);
  }

  // Ray l, as loaded.
  MLIB_INLINE Ray ray(int l) const {
    return Ray(vec4(org[0][l], org[1][l], org[2][l], org_w[l]),
               vec4(dir[0][l], dir[1][l], dir[2][l], dir_w[l]));
  }

  // t_max_padded = t * kSlabPad for every lane (t_max_padded is 64-byte aligned); returns
  // the largest, NaN lanes left out.
  MLIB_INLINE static float pad_and_max(const float* t, float* t_max_padded) {
    R m = R::broadcast(0.0f);
    for (int c = 0; c < kPacketSize; c += kRayLanes) {
      const R p = R::load(t + c) * R::broadcast(kSlabPad);
      p.store(t_max_padded + c);
      m = max(p, m);  // a NaN lane of p (a NaN t_max) keeps m, as std::max(t_far, NaN) would
    }
    alignas(64) float x[kRayLanes];
    mlib::reduce_max(m).store(x);
    return x[0];
  }

  // The value of r's lanes (all equal) in every lane of a V.
  MLIB_INLINE static V widen(R r) {
    alignas(64) float x[kRayLanes];
    r.store(x);
    return V::broadcast(x[0]);
  }

  // After load: the reciprocals and the frustum. Returns false when the rays cannot walk
  // together: their directions' signs differ on an axis, or a component of a direction is
  // zero (an infinite reciprocal).
  bool make_frustum() {
    constexpr PacketMask kAll = (PacketMask(1) << kPacketSize) - 1;
    const R one = R::broadcast(1.0f), pad = R::broadcast(kSlabPad), zero = R::broadcast(0.0f),
            inf = R::broadcast(kInfinity), minus_inf = R::broadcast(-kInfinity);
    for (int a = 0; a < 3; ++a) {
      R o_lo = inf, o_hi = minus_inf, i_lo = inf, i_hi = minus_inf, f_lo = inf, f_hi = minus_inf;
      PacketMask negative = 0, finite = 0;
      for (int c = 0; c < kPacketSize; c += kRayLanes) {
        const R d = R::load(dir[a] + c), o = R::load(org[a] + c);
        const R inv = one / d;  // as RayPre computes it
        const R inv_f = inv * pad;
        inv.store(inv_near[a] + c);
        inv_f.store(inv_far[a] + c);
        negative |= PacketMask(mlib::bits(d < zero)) << c;
        finite |= PacketMask(mlib::bits(abs(inv) < inf)) << c;
        o_lo = min(o_lo, o), o_hi = max(o_hi, o);
        i_lo = min(i_lo, inv), i_hi = max(i_hi, inv);
        f_lo = min(f_lo, inv_f), f_hi = max(f_hi, inv_f);
      }
      // A zero component (-0 included) has an infinite reciprocal.
      if (finite != kAll || (negative != 0 && negative != kAll)) return false;
      near[a] = 2 * a + (negative ? 1 : 0);
      far[a] = near[a] ^ 1;
      // Positive direction: the near plane is a box's low side, nearest to the largest
      // origin; negative: its high side, nearest to the smallest origin.
      o_near[a] = widen(negative ? mlib::reduce_min(o_lo) : mlib::reduce_max(o_hi));
      o_far[a] = widen(negative ? mlib::reduce_max(o_hi) : mlib::reduce_min(o_lo));
      i_near[a] = widen(negative ? mlib::reduce_max(i_hi) : mlib::reduce_min(i_lo));  // smallest |.|
      i_far[a] = widen(negative ? mlib::reduce_min(f_lo) : mlib::reduce_max(f_hi));   // largest |.|
    }
    return true;
  }

  // load and make_frustum (false also when a ray has a NaN coordinate).
  bool make(const Ray* rays, PacketMask lanes) {
    if (load(rays, lanes) != lanes) return false;
    return make_frustum();
  }

  // The frustum against a node's N child boxes: bit i set when some ray may enter child i
  // within [t_min, t_max_padded / kSlabPad], `entry` a lower bound of their entry
  // distances. As NodeRay::test (the integer form), with the frustum's bounds.
  template <class Node>
  MLIB_INLINE unsigned test(const Node& node, V t_min, V t_max_padded, V& entry) const {
    V n[3], f[3];
    for (int a = 0; a < 3; ++a) {
      n[a] = (node_row(node, near[a]) - o_near[a]) * i_near[a];
      f[a] = (node_row(node, far[a]) - o_far[a]) * i_far[a];
    }
    entry = imax(imax(n[0], n[1]), imax(n[2], t_min));
    return mlib::bits(ile(entry, imin(imin(f[0], f[1]), imin(f[2], t_max_padded)))) &
           used_slots(node);
  }

  // The lanes of `lanes` whose rays enter child `slot` of `node` within [t_min,
  // t_max_padded[l] / kSlabPad]: each ray's own test (NodeRay<N, true>::test), kRayLanes
  // rays at a time.
  template <class Node>
  MLIB_INLINE PacketMask enter(const Node& node, int slot, PacketMask lanes, R t_min,
                               const float* t_max_padded) const {
    R lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] = R::broadcast(node.plane(near[a], slot));
      hi[a] = R::broadcast(node.plane(far[a], slot));
    }
    PacketMask mask = 0;
    for (int c = 0; c < kPacketSize; c += kRayLanes) {
      if (!(lanes >> c & kChunk)) continue;
      R n[3], f[3];
      for (int a = 0; a < 3; ++a) {
        const R o = R::load(org[a] + c);
        n[a] = (lo[a] - o) * R::load(inv_near[a] + c);
        f[a] = (hi[a] - o) * R::load(inv_far[a] + c);
      }
      const R entry = imax(imax(n[0], n[1]), imax(n[2], t_min));
      const R exit = imin(imin(f[0], f[1]), imin(f[2], R::load(t_max_padded + c)));
      mask |= PacketMask(mlib::bits(ile(entry, exit))) << c;
    }
    return mask & lanes;
  }
};

// A pending subtree of a packet walk: the rays that enter its box (each by its own test),
// and their entry distance's lower bound (closest hit only).
struct PacketStackEntry {
  std::uint32_t ref;
  float t;
  PacketMask rays;
};

// Walks counted as packets, and the rays they carried.
MLIB_INLINE void count_packet(TraversalCounts& c, PacketMask lanes) {
  ++c.packets;
  c.packet_rays += static_cast<unsigned>(std::popcount(lanes));
}

// The closest triangle hit of each ray l of `lanes` in (t_min, hits[l].t), updating
// hits[l] as closest_triangle_walk does (ties to the smaller index). t_bound holds every
// lane's hits[l].t (kPacketSize floats, 64-byte aligned; the lanes outside `lanes` are not
// read), whole vectors where the rays' bounds were just computed. `test` tests a leaf
// block against the packet's rays (triangle_packet_intersect.h); `pr` was made from the
// same rays and lanes.
template <int N, class PacketTest, class Node>
inline void closest_triangle_packet_walk(const WideBvh<N>& bvh, const Node* nodes,
                                         const TriangleBlock* blocks, const PacketRays<N>& pr,
                                         const PacketTest& test, PacketMask lanes, float t_min,
                                         const float* t_bound, Hit* hits,
                                         TraversalCounts* counts) {
  using V = mlib::vfloat<N>;
  const V t_min_v = V::broadcast(t_min);
  const typename PacketRays<N>::R t_min_r = PacketRays<N>::R::broadcast(t_min);
  TraversalCounts local;
  count_packet(local, lanes);
  // Per ray: its best hit's t so far, and that padded as the box tests take it (0 for the
  // lanes outside the packet, which no test reads, so that the largest is t_far).
  alignas(64) float t_best[kPacketSize];
  alignas(64) float t_max_padded[kPacketSize];
  using R = typename PacketRays<N>::R;
  for (int c = 0; c < kPacketSize; c += R::size)
    select(R::bool_type::from_bits(lanes >> c & PacketRays<N>::kChunk), R::load(t_bound + c),
           R::broadcast(0.0f))
        .store(t_best + c);
  // t_far: no ray hits anything beyond it.
  float t_far = pr.pad_and_max(t_best, t_max_padded);
  PacketStackEntry stack[kStackSize<N>];
  int sp = 0;
  std::uint32_t ref = bvh.root;
  PacketMask rays = lanes;  // the rays that enter ref's box
  alignas(64) float entry_t[N];
  for (;;) {
    while (!(ref & kLeaf)) {
      ++local.nodes;
      const Node& node = nodes[ref];
      V entry;
      unsigned mask = pr.test(node, t_min_v, V::broadcast(t_far), entry);
      entry.store(entry_t);
      // The children some ray enters, nearest first; the others go on the stack, farthest
      // deepest.
      PacketStackEntry hit[N];
      int k = 0;
      for (; mask; mask &= mask - 1) {
        const int i = std::countr_zero(mask);
        const PacketMask in = pr.enter(node, i, rays, t_min_r, t_max_padded);
        if (in) hit[k++] = {node.child[i], entry_t[i], in};
      }
      if (k == 0) goto pop;
      for (int a = 1; a < k; ++a)
        for (int j = a; j > 0 && hit[j - 1].t < hit[j].t; --j) std::swap(hit[j - 1], hit[j]);
      for (int j = 0; j < k; ++j) prefetch_ref(nodes, blocks, hit[j].ref);
      for (int j = 0; j < k - 1; ++j) stack[sp++] = hit[j];
      ref = hit[k - 1].ref;
      rays = hit[k - 1].rays;
    }
    // A leaf.
    for (const TriangleBlock* b = blocks + (ref & ~kLeaf);; ++b) {
      local.blocks += static_cast<unsigned>(std::popcount(rays));
      test.nearest(*b, rays, t_min, hits, t_best);
      if (b->last()) break;
    }
    t_far = pr.pad_and_max(t_best, t_max_padded);
  pop:
    for (;;) {
      if (sp == 0) {
        if (counts) *counts += local;
        return;
      }
      const PacketStackEntry& e = stack[--sp];
      if (e.t <= t_far) {
        ref = e.ref;
        rays = e.rays;
        break;
      }
    }
  }
}

// Calls on_hit(l, prim, t) for triangles hit by ray l of `lanes` in (t_min, t_max[l]), in
// no particular order, until it returns true for that ray (then the ray is done). Returns
// the lanes for which it did. t_max holds kPacketSize floats (those outside `lanes` unused).
template <int N, class PacketTest, class Node, class OnHit>
inline PacketMask any_triangle_packet_walk(const WideBvh<N>& bvh, const Node* nodes,
                                           const TriangleBlock* blocks, const PacketRays<N>& pr,
                                           const PacketTest& test, PacketMask lanes, float t_min,
                                           const float* t_max, OnHit&& on_hit,
                                           TraversalCounts* counts) {
  using V = mlib::vfloat<N>;
  const V t_min_v = V::broadcast(t_min);
  const typename PacketRays<N>::R t_min_r = PacketRays<N>::R::broadcast(t_min);
  TraversalCounts local;
  count_packet(local, lanes);
  alignas(64) float t_max_padded[kPacketSize];
  alignas(64) float t_below[kPacketSize];  // the block test's inclusive bound, below t_max
  // A vector at a time (t_max holds kPacketSize floats; lanes outside `lanes` take 0):
  // float_below is one step down in the bits where t is positive, std::nextafter elsewhere.
  using R = typename PacketRays<N>::R;
  const R zero = R::broadcast(0.0f);
  R far = zero;
  for (int c = 0; c < kPacketSize; c += R::size) {
    const unsigned chunk = lanes >> c & PacketRays<N>::kChunk;
    const R t = select(R::bool_type::from_bits(chunk), R::loadu(t_max + c), zero);
    const R padded = t * R::broadcast(kSlabPad);
    padded.store(t_max_padded + c);
    far = max(padded, far);  // a NaN lane keeps far, as std::max(t_far, NaN) would
    const auto positive = (t > zero) & (t <= R::broadcast(kInfinity));
    select(positive, step_ulps(t, R::broadcast(-1.0f)), t).store(t_below + c);
    for (unsigned m = chunk & ~mlib::bits(positive); m; m &= m - 1)
      t_below[c + std::countr_zero(m)] = float_below(t_max[c + std::countr_zero(m)]);
  }
  alignas(64) float far_lanes[R::size];
  mlib::reduce_max(far).store(far_lanes);
  const V t_far_v = V::broadcast(far_lanes[0]);
  PacketMask open = lanes, done = 0;  // open: the rays not yet blocked
  PacketStackEntry stack[kStackSize<N>];
  int sp = 0;
  std::uint32_t ref = bvh.root;
  PacketMask rays = lanes;  // the open rays that enter ref's box
  for (;;) {
    while (!(ref & kLeaf)) {
      ++local.nodes;
      const Node& node = nodes[ref];
      V entry;
      unsigned mask = pr.test(node, t_min_v, t_far_v, entry);
      PacketMask next = 0;
      for (; mask; mask &= mask - 1) {
        const int i = std::countr_zero(mask);
        const PacketMask in = pr.enter(node, i, rays, t_min_r, t_max_padded);
        if (!in) continue;
        if (next) stack[sp++] = {ref, 0.0f, next};  // the previous child (ref reused below)
        ref = node.child[i];  // tentatively the child walked next
        next = in;
        prefetch_ref(nodes, blocks, ref);
      }
      if (!next) goto pop;
      rays = next;
    }
    for (const TriangleBlock* b = blocks + (ref & ~kLeaf);; ++b) {
      local.blocks += static_cast<unsigned>(std::popcount(rays));
      done |= test.any(*b, rays, t_min, t_below, on_hit);
      rays &= ~done;
      if (!rays || b->last()) break;
    }
    open &= ~done;
    if (!open) break;
  pop:
    for (;;) {
      if (sp == 0) goto out;
      --sp;
      ref = stack[sp].ref;
      rays = stack[sp].rays & open;
      if (rays) break;
    }
  }
out:
  if (counts) *counts += local;
  return done;
}

// closest_triangle_packet_walk over the tree's nodes, of either layout.
template <int N, class PacketTest>
inline void closest_triangle_packet(const WideBvh<N>& bvh, const TriangleBlock* blocks,
                                    const PacketRays<N>& pr, const PacketTest& test,
                                    PacketMask lanes, float t_min, const float* t_bound,
                                    Hit* hits, TraversalCounts* counts) {
  with_walk_nodes(bvh, [&](const auto* nodes) {
    closest_triangle_packet_walk(bvh, nodes, blocks, pr, test, lanes, t_min, t_bound, hits,
                                 counts);
  });
}

// any_triangle_packet_walk over the tree's nodes, of either layout.
template <int N, class PacketTest, class OnHit>
inline PacketMask any_triangle_packet(const WideBvh<N>& bvh, const TriangleBlock* blocks,
                                      const PacketRays<N>& pr, const PacketTest& test,
                                      PacketMask lanes, float t_min, const float* t_max,
                                      OnHit&& on_hit, TraversalCounts* counts) {
  return with_walk_nodes(bvh, [&](const auto* nodes) {
    return any_triangle_packet_walk(bvh, nodes, blocks, pr, test, lanes, t_min, t_max, on_hit,
                                    counts);
  });
}

}  // namespace rt2::RT2_ISA
