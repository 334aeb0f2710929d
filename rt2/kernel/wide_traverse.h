// rt2/kernel/wide_traverse.h — walking the wide BVH (bvh/wide_bvh.h) with one ray: the
// closest hit, and an any-hit walk for shadow rays.
//
// A node's N child boxes are tested in one SIMD pass (the slab test, Kay and Kajiya 1986),
// near and far rows picked once per ray from its direction's signs (Embree's TravRay), with
// Ize's robust padding (2013: far distances times 1 + 2 gamma(3)) so rounding never culls a
// box the ray touches. Closest hit: children visited nearest first (two: ordered; three or
// more: pushed in the node's order for the ray's octant), ties between triangles at equal t
// to the smaller index, so every width (every ISA) finds the same hit, bit for bit. Any hit:
// no ordering, stops as soon as `on_hit` says so.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <utility>

#include "rt2/kernel/kernel.h"

#include "mlib/vfloat.h"
#include "rt2/geometry/aabb.h"
#include "rt2/bvh/wide_bvh.h"
#include "rt2/kernel/triangle_block_intersect.h"

namespace rt2::RT2_ISA {

// Whether the node test of N lanes takes its fused form (mlib's fmadd: the AVX2 kernels'
// vfloat8, the AVX-512 kernels' vfloat16).
template <int N>
inline constexpr bool kFusedNodeTest =
    requires(mlib::vfloat<N> a) { fmadd(a, a, a); };  // found through a (mlib)

// Row `row` of a node's child planes in N lanes (WideNode::bounds), for either layout: a
// quantized node's decoded as QuantizedNode::plane decodes it (an exact product, rounded
// once in the sum, fused or not).
template <int N>
MLIB_INLINE mlib::vfloat<N> node_row(const WideNode<N>& node, int row) {
  return mlib::vfloat<N>::load(node.bounds[row]);
}
template <int N>
MLIB_INLINE mlib::vfloat<N> node_row(const QuantizedNode<N>& node, int row) {
  using V = mlib::vfloat<N>;
  const V scale = V::broadcast(node.scale(row >> 1));
  if constexpr (kFusedNodeTest<N>)
    return fmadd(V::from_bytes(node.q[row]), scale, V::broadcast(node.origin[row]));
  else
    return V::from_bytes(node.q[row]) * scale + V::broadcast(node.origin[row]);
}

// f(nodes) with bvh's nodes, of either layout. The call on quantized nodes stays out of line,
// so that the plain walks' callers are compiled as they are without it (inlined beside them,
// it slowed their single rays: docs/performance.md).
template <class F, class Node>
[[gnu::noinline]] decltype(auto) out_of_line(F& f, const Node* nodes) {
  return f(nodes);
}
template <int N, class F>
MLIB_INLINE decltype(auto) with_walk_nodes(const WideBvh<N>& bvh, F&& f) {
  if (bvh.quantized) [[unlikely]]
    return out_of_line(f, bvh.quantized_nodes.data());
  return f(bvh.nodes.data());
}

// The slots a node test may report: a plain node's unused slots have empty boxes, which no
// ray enters; a quantized node's are masked.
template <int N>
MLIB_INLINE unsigned used_slots(const WideNode<N>&) {
  return ~0u;
}
template <int N>
MLIB_INLINE unsigned used_slots(const QuantizedNode<N>& node) {
  return node.used;
}

// The ray as the node test needs it, for N lanes. `Finite`: every component of 1/dir is
// finite (and org * 1/dir far from overflow, tree_form below), so no slab distance can be NaN
// and the test takes its short form: minima and maxima as a tree of integer operations on
// the floats' bits (one cycle each, where minps and maxps take four: this chain runs from
// one node to the next; Embree's trick). Integer order is float order for non-negative
// values and ranks every negative value lowest. The entry distance is a maximum that
// includes t_min >= 0 and the exit distance a minimum that includes t_max >= 0, so a box is
// entered exactly when the float test says so, with one exception: an exit distance of -0
// (an origin exactly on a box's far plane, leaving it) ranks lowest and the box is skipped,
// where the float test would keep it. Nothing the triangle test could accept is lost: every
// triangle in the box lies at least the box's padding (4 ulps, build.cpp) behind such an
// origin, the margin the padding leaves for the triangle test's rounding anywhere.
// Otherwise (a zero direction component) the float form, in an order that lets a NaN
// distance fall away (see above).
//
// The fused form (kFusedNodeTest, with Finite): a slab distance (b - org) / dir is
// b * inv + c, one FMA from the plane b, with c = -org * inv computed once per ray (as
// Embree's fast mode): a multiply off the chain each node waits on. The rounded c may
// be off by half an ulp of org * inv, which is no small part of a distance when the origin
// lies far from the coordinate origin and near the box (the boxes' padding, 4 ulps of
// their coordinates, would absorb it, but the bound should not lean on that). So c carries
// a margin of four ulps of itself or more (and 2^-125 for a c flushed to zero): c_near lies
// below and c_far above the exact value. Then a near distance is the exact one rounded once
// after a shift down, and a far one the exact (b - org) * inv_far rounded once after a
// shift up: each errs less, in the direction that matters, than the two roundings of
// (b - org) * inv that Ize's padding (kSlabPad) covers. A c moved the wrong way by 2^-20
// of itself (8-16 ulps) loses hits in five tests (bvh_test's far-soup test among them).
template <int N, bool Finite>
struct NodeRay {
  using V = mlib::vfloat<N>;
  static constexpr bool kFused = Finite && kFusedNodeTest<N>;
  // The ray's constants. The 16-wide kernels keep them as floats and broadcast them where a
  // node is tested: GCC 12 spills such vectors in their walks (a 64-byte store each per
  // ray), and a broadcast from memory is one load, as a reload is. The 4- and 8-wide
  // kernels keep vectors, which measured faster there.
  using Constant = std::conditional_t<(N >= 16), float, V>;
  Constant org[3], inv_near[3], inv_far[3];
  Constant c_near[3], c_far[3];  // the fused form's offsets
  int near[3], far[3];  // box rows (WideNode::bounds)
  int order_shift;  // kOrderBits<N> x the ray's octant: where WideNode::octant_order
                    // keeps its order

  // A constant as stored (constant) and as the node test uses it (lanes).
  static MLIB_INLINE Constant constant(float c) {
    if constexpr (std::is_same_v<Constant, float>)
      return c;
    else
      return V::broadcast(c);
  }
  static MLIB_INLINE V lanes(float c) { return V::broadcast(c); }
  static MLIB_INLINE V lanes(V c) { return c; }

  explicit NodeRay(const Ray& r, const RayPre& pre) {
    // 1/dir is +-inf for a zero component, with the zero's sign: the sign bits decide, all
    // three read at once.
    const unsigned negative = unsigned(mlib::simd::movemask(pre.inv_dir.m128())) & 7u;
    order_shift = kOrderBits<N> * int(negative);
    for (int a = 0; a < 3; ++a) {
      near[a] = 2 * a + int(negative >> a & 1u);
      far[a] = near[a] ^ 1;
      org[a] = constant(r.org[a]);
      inv_near[a] = constant(pre.inv_dir[a]);
      // Far distances carry Ize's 1 + 2 gamma(3) in the reciprocal: the same three
      // roundings before the padding as (far - org) * inv * pad, one multiply less per node.
      const float inv_far_s = pre.inv_dir[a] * kSlabPad;
      inv_far[a] = constant(inv_far_s);
      if constexpr (kFused) {
        // One margin for both: eight ulps of org * inv, which is more than four of
        // org * inv_far (inv_far exceeds inv by 2^-21 of itself at most).
        const float p = r.org[a] * pre.inv_dir[a], p_far = r.org[a] * inv_far_s;
        const float margin = std::fabs(p) * 0x1p-21f + 0x1p-125f;
        c_near[a] = constant(-(p + margin));
        c_far[a] = constant(margin - p_far);
      }
    }
  }

  // Bit i set when child i's box is entered within [t_min, t_max_padded / pad]; its entry
  // in `entry`. The caller pads t_max: t_max_padded = t_max * kSlabPad (>= 0, as t_min).
  template <class Node>
  MLIB_INLINE unsigned test(const Node& node, V t_min, V t_max_padded, V& entry) const {
    V n[3], f[3];
    for (int a = 0; a < 3; ++a) {
      if constexpr (kFused) {
        n[a] = fmadd(node_row(node, near[a]), lanes(inv_near[a]), lanes(c_near[a]));
        f[a] = fmadd(node_row(node, far[a]), lanes(inv_far[a]), lanes(c_far[a]));
      } else {
        n[a] = (node_row(node, near[a]) - lanes(org[a])) * lanes(inv_near[a]);
        f[a] = (node_row(node, far[a]) - lanes(org[a])) * lanes(inv_far[a]);
      }
    }
    if constexpr (Finite) {
      entry = imax(imax(n[0], n[1]), imax(n[2], t_min));
      return mlib::bits(ile(entry, imin(imin(f[0], f[1]), imin(f[2], t_max_padded)))) &
             used_slots(node);
    } else {  // NaN first: max / min then return the other operand
      entry = max(n[2], max(n[1], max(n[0], t_min)));
      return mlib::bits(entry <= min(f[2], min(f[1], min(f[0], t_max_padded)))) &
             used_slots(node);
    }
  }
};

// Whether the node test may take the tree form: every 1/dir component finite, and every
// org * 1/dir (the fused form's offset, with its margin) far from overflow; the three axes
// in one vfloat4 comparison.
MLIB_INLINE bool tree_form(const Ray& r, const RayPre& pre) {
  const vfloat4 inv = vfloat4::from_f4(pre.inv_dir.m128()), org = vfloat4::from_f4(r.org.m128());
  const auto ok = (abs(inv) < vfloat4::broadcast(kInfinity)) &  // false for NaN as well
                  (abs(org * inv) < vfloat4::broadcast(0x1p126f));
  return (mlib::bits(ok) & 7u) == 7u;  // x, y and z
}

// The largest float below t (for t > 0; std::nextafter otherwise), without a library call.
MLIB_INLINE float float_below(float t) {
  if (t > 0.0f && t <= std::numeric_limits<float>::infinity())
    return std::bit_cast<float>(std::bit_cast<std::uint32_t>(t) - 1u);  // inf -> FLT_MAX
  return std::nextafter(t, -kInfinity);
}

// A pending subtree and the distance at which the ray enters it.
struct StackEntry {
  std::uint32_t ref;
  float t;
};

// Deepest stack: each level of the tree pushes at most N - 1 entries.
template <int N>
inline constexpr int kStackSize = (N - 1) * (kMaxBvhDepth + 1) + 1;

// Whether the walks push three or more children in an octant order with
// mlib::compress_in_order (vfloat8 and vfloat16: the AVX2 and AVX-512 kernels): the
// closest-hit walk rather than sorting them, the any-hit walk rather than pushing them one
// by one.
template <int N>
inline constexpr bool kPushInOctantOrder =
    requires(mlib::vfloat<N> t, const std::uint32_t* p, std::uint32_t* q, float* f) {
      compress_in_order(t, p, p, 0, 0u, f, q);  // found through t (mlib)
    };

// The eight lanes in which the 8- and 16-wide walks test two leaves' first blocks at once.
// Spelled with N so that the 4-wide kernels, built without a vfloat8, never name it.
template <int N>
using PairLanes = mlib::vfloat<(N < 8 ? N : 8)>;

// Lines of a node, and of a leaf block, fetched together when the walk decides to go there:
// the first one would stall anyway, the others then arrive during that wait.
// A node aligned to less than a line starts anywhere its alignment allows.
template <class Node>
inline constexpr int kNodeLines = int((sizeof(Node) + (64 - alignof(Node)) + 63) / 64);
// A block starts anywhere its alignment allows, so it may reach into one line more.
inline constexpr int kBlockLines =
    int((sizeof(TriangleBlock) + (64 - alignof(TriangleBlock)) + 63) / 64);
static_assert(kBlockLines == 4);

template <class Node>
MLIB_INLINE void prefetch_ref(const Node* nodes, const TriangleBlock* blocks, std::uint32_t ref) {
  if (ref & kLeaf)
    mlib::prefetch(blocks + (ref & ~kLeaf), kBlockLines);
  else
    mlib::prefetch(nodes + ref, kNodeLines<Node>);
}

// The nodes and blocks a walk visits, counted only when the caller asks for them (Count;
// with_walk_form picks the walk by `counts`): the walks' loops are short of registers, and
// two live counters push the stack index, the node pointer and some of the ray's constants
// out to memory. For the same reason the walks hold the node pointer and the prefetch flag
// in locals and return the hit by value.
template <bool Count>
struct WalkCounts {
  TraversalCounts c;
  void node() { ++c.nodes; }
  void blocks(int k) { c.blocks += std::uint64_t(k); }
  void add_to(TraversalCounts* out) const { *out += c; }
};
template <>
struct WalkCounts<false> {
  void node() {}
  void blocks(int) {}
  void add_to(TraversalCounts*) const {}
};

// What the closest-hit walk returns: a Hit without its instance, 16 bytes, which GCC 12
// returns in registers.
struct TriangleHit {
  float t = kInfinity;
  float u = 0.0f, v = 0.0f;
  PrimRef prim = kNoHit;
  bool found() const { return prim != kNoHit; }
};

// The closest triangle hit by `ray` in (t_min, t_max), or at t_max itself when `prior` is
// a hit there (a plane or a sphere, which a triangle at the same t beats): a Hit with t, u,
// v and prim = the triangle's index when one is found, else t = t_max and prim = prior.
// Ties at equal t go to the smaller index. `test` is a FastTriangleTest or a
// WatertightTriangleTest built from `ray` (taken by reference: by value, GCC 12 keeps a
// copy in memory). The earlier hit comes in as two scalars, not as a Hit by value: GCC 12
// assembles that argument on the stack from 4-byte stores and reads it back as two 8-byte
// halves, a load that no store can forward.
template <int N, class Test, bool Finite, bool Count, class Node>
inline TriangleHit closest_triangle_walk(const WideBvh<N>& bvh, const Node* const nodes,
                                         const TriangleBlock* blocks,
                                         const Ray& ray, const RayPre& pre, const Test& test,
                                         float t_min, float t_max, PrimRef prior,
                                         TraversalCounts* counts) {
  using V = mlib::vfloat<N>;
  TriangleHit h;
  h.t = t_max;
  h.prim = prior;
  const NodeRay<N, Finite> nr(ray, pre);
  const V t_min_v = V::broadcast(t_min);
  const vfloat4 t_min_4 = vfloat4::broadcast(t_min);
  WalkCounts<Count> local;
  // The pending subtrees and their entry distances, side by side (compress_in_order
  // writes N lanes at a time: N - 1 entries of slack).
  alignas(64) std::uint32_t stack_ref[kStackSize<N> + N - 1];
  alignas(64) float stack_t[kStackSize<N> + N - 1];
  std::size_t sp = 0;
  std::uint32_t ref = bvh.root;
  const bool prefetch_pushed = bvh.prefetch_pushed;
  alignas(64) float entry_t[N];
  // Takes the hit n, lane `lane` of block b, when it is nearer than h (or as near, with a
  // smaller triangle index).
  const auto take = [&h](const TriangleBlock& b, const NearestHit& n, int lane) {
    const std::uint32_t prim = b.prim_of(lane);
    if (n.t < h.t || (n.t == h.t && h.found() && prim < h.prim)) {
      h.t = n.t;
      h.u = n.u;
      h.v = n.v;
      h.prim = prim;
    }
  };
  for (;;) {
    // Down through inner nodes, nearest child first.
    while (!(ref & kLeaf)) {
      local.node();
      const Node& node = nodes[ref];
      V entry;
      const unsigned mask = nr.test(node, t_min_v, V::broadcast(h.t * kSlabPad), entry);
      if (mask == 0) goto pop;
      const unsigned rest = mask & (mask - 1);
      if (rest == 0) {  // one child: no stack
        ref = node.child[std::countr_zero(mask)];
        prefetch_ref(nodes, blocks, ref);
        continue;
      }
      if constexpr (kPushInOctantOrder<N>) {
        if (rest & (rest - 1)) {  // three or more: pushed in their octant order, the
                                  // nearest (roughly) on top, without a branch per child
          const int pushed = compress_in_order(entry, node.child, node.octant_order,
                                               nr.order_shift, mask, stack_t + sp, stack_ref + sp);
          if (prefetch_pushed)  // a large tree: all of them (WideBvh::prefetch_pushed)
            for (int j = 0; j < pushed - 1; ++j) prefetch_ref(nodes, blocks, stack_ref[sp + j]);
          sp += std::size_t(pushed - 1);
          ref = stack_ref[sp];
          prefetch_ref(nodes, blocks, ref);
          continue;
        }
      }
      entry.store(entry_t);
      const unsigned i = static_cast<unsigned>(std::countr_zero(mask));
      const unsigned i1 = static_cast<unsigned>(std::countr_zero(rest));
      if ((rest & (rest - 1)) == 0) {  // two (one node in four): push the farther, selected
                                       // without a branch (a mispredicted one costs more
                                       // than the whole node test)
        const StackEntry a{node.child[i], entry_t[i]}, b{node.child[i1], entry_t[i1]};
        if constexpr (N >= 8) {
          if (a.ref & b.ref & kLeaf) {  // two leaves: their first blocks in one 8-wide pass
            const TriangleBlock* ba = blocks + (a.ref & ~kLeaf);
            const TriangleBlock* bb = blocks + (b.ref & ~kLeaf);
            local.blocks(2);
            const NearestHit n = test.nearest_pair(*ba, *bb, PairLanes<N>::broadcast(t_min),
                                                   PairLanes<N>::broadcast(h.t));
            if (n.lane >= 0) take(n.lane < 4 ? *ba : *bb, n, n.lane & 3);
            // A leaf of more blocks: the rest of it, as a leaf of its own, later.
            if (!ba->last()) stack_ref[sp] = a.ref + 1, stack_t[sp++] = a.t;
            if (!bb->last()) stack_ref[sp] = b.ref + 1, stack_t[sp++] = b.t;
            goto pop;
          }
        }
        const bool a_first = a.t <= b.t;
        const StackEntry farther = a_first ? b : a;
        stack_ref[sp] = farther.ref;
        stack_t[sp++] = farther.t;
        prefetch_ref(nodes, blocks, farther.ref);
        ref = a_first ? a.ref : b.ref;
        prefetch_ref(nodes, blocks, ref);
        continue;
      }
      // Three or more in the 4-wide tree: sorted by entry distance, farthest first.
      StackEntry hit[N];
      int k = 0;
      for (unsigned m = mask; m; m &= m - 1) {
        const unsigned c = static_cast<unsigned>(std::countr_zero(m));
        hit[k++] = {node.child[c], entry_t[c]};
      }
      for (int a = 1; a < k; ++a)
        for (int j = a; j > 0 && hit[j - 1].t < hit[j].t; --j) std::swap(hit[j - 1], hit[j]);
      for (int j = 0; j < k; ++j) prefetch_ref(nodes, blocks, hit[j].ref);
      for (int j = 0; j < k - 1; ++j) {
        stack_ref[sp] = hit[j].ref;
        stack_t[sp++] = hit[j].t;
      }
      ref = hit[k - 1].ref;
    }
    // A leaf: its blocks, until the one marked last.
    for (const TriangleBlock* b = blocks + (ref & ~kLeaf);; ++b) {
      local.blocks(1);
      const NearestHit n = test.nearest(*b, t_min_4, vfloat4::broadcast(h.t));
      if (n.lane >= 0) take(*b, n, n.lane);
      if (b->last()) break;
    }
  pop:
    for (;;) {  // the next pending subtree that can still hold a closer hit (or a tie)
      if (sp == 0) {
        local.add_to(counts);
        return h;
      }
      --sp;
      if (stack_t[sp] <= h.t * kSlabPad) {
        ref = stack_ref[sp];
        break;
      }
    }
  }
}

// Whether `ray` may meet the tree within [t_min, t_max]: its origin lies in the tree's box
// (WideBvh::bounds), or it enters the box by the slab test the binary tree's walk makes (aabb.h:
// conservative, so no triangle hit is lost). A ray that misses the box then costs neither the
// walk's per-ray set-up (the node ray's constants, the walk's frame) nor its first node test:
// camera rays miss a mesh's box wherever it does not fill the image. The origin test comes
// first: rays that start inside the box (from a surface, as reflections do) pay two compares,
// not the slab test. The closest-hit walk only: shadow rays leave surfaces, and there the test
// costs more than it saves.
template <int N>
MLIB_INLINE bool may_enter(const WideBvh<N>& bvh, const Ray& ray, const RayPre& pre, float t_min,
                           float t_max) {
  return bvh.bounds.contains(ray.org) ||
         slab_entry(bvh.bounds.lo, bvh.bounds.hi, pre, t_min, t_max) != kInfinity;
}

// walk(finite, count) with the walks' two compile-time choices as std::bool_constant:
// Finite (the ray takes the node test's tree form) and Count (the caller wants counts).
template <class Walk>
MLIB_INLINE decltype(auto) with_walk_form(const Ray& ray, const RayPre& pre,
                                          const TraversalCounts* counts, Walk&& walk) {
  using yes = std::true_type;
  using no = std::false_type;
  if (tree_form(ray, pre)) return counts ? walk(yes{}, yes{}) : walk(yes{}, no{});
  return counts ? walk(no{}, yes{}) : walk(no{}, no{});
}

// The prior a walk of instance `instance`'s tree starts from, for ties at h.t: h.prim, or
// h.prim + 1 when h is a hit of an instance of a larger index (or of the world's own
// geometry), so that the same triangle at the same t goes to the smaller instance. Ties thus
// go to the smaller (primitive, instance), whatever order the instances are walked in.
MLIB_INLINE PrimRef tie_prior(const Hit& h, std::uint32_t instance) {
  return h.found() && instance < h.instance ? h.prim + 1 : h.prim;
}

// The closest triangle hit into h when one is nearer than h.t (or as near, and first by
// (index, instance), tie_prior); returns whether one was. `instance` is what h.instance
// becomes then.
template <int N, class Test>
MLIB_INLINE bool closest_triangle(const WideBvh<N>& bvh, const TriangleBlock* blocks,
                                  const Ray& ray, const Test& test, float t_min, Hit& h,
                                  TraversalCounts* counts, std::uint32_t instance = kNoInstance) {
  if (bvh.root == kNoChild) return false;
  const RayPre pre(ray);
  if (!may_enter(bvh, ray, pre, t_min, h.t)) return false;
  const PrimRef prior = tie_prior(h, instance);
  const TriangleHit t = with_walk_nodes(bvh, [&](const auto* nodes) {
    return with_walk_form(ray, pre, counts, [&](auto finite, auto count) {
      return closest_triangle_walk<N, Test, decltype(finite)::value, decltype(count)::value>(
          bvh, nodes, blocks, ray, pre, test, t_min, h.t, prior, counts);
    });
  });
  if (t.prim == prior && t.t == h.t) return false;
  h = Hit{t.t, t.u, t.v, t.prim, instance};
  return true;
}

// Calls on_hit(prim, t) for triangles hit by `ray` in (t_min, t_max), in no particular
// order, until it returns true; returns whether it did.
template <int N, class Test, bool Finite, bool Count, class Node, class OnHit>
inline bool any_triangle_walk(const WideBvh<N>& bvh, const Node* const nodes,
                              const TriangleBlock* blocks, const Ray& ray,
                              const RayPre& pre, const Test& test, float t_min, float t_max,
                              OnHit&& on_hit, TraversalCounts* counts) {
  using V = mlib::vfloat<N>;
  const NodeRay<N, Finite> nr(ray, pre);
  const V t_min_v = V::broadcast(t_min), t_max_v = V::broadcast(t_max * kSlabPad);
  const vfloat4 t_min_4 = vfloat4::broadcast(t_min);
  // Inclusive upper bound of the block test, strictly below t_max.
  const float t_below = float_below(t_max);
  const vfloat4 t_below_4 = vfloat4::broadcast(t_below);
  WalkCounts<Count> local;
  alignas(64) std::uint32_t stack[kStackSize<N> + N - 1];  // slack: compress_in_order
  std::size_t sp = 0;
  std::uint32_t ref = bvh.root;
  bool stopped = false;
  for (;;) {
    while (!(ref & kLeaf)) {
      local.node();
      const Node& node = nodes[ref];
      V entry;
      unsigned mask = nr.test(node, t_min_v, t_max_v, entry);
      if (mask == 0) goto pop;
      if constexpr (kPushInOctantOrder<N>) {
        const unsigned rest = mask & (mask - 1);
        if (rest & (rest - 1)) {  // three or more: pushed in one step, in the order of the
                                  // opposite octant, so the farthest is walked first (an
                                  // occluder often lies toward the light rather than beside
                                  // the surface a shadow ray leaves)
          alignas(64) float unused_t[N];
          sp += std::size_t(compress_in_order(entry, node.child, node.octant_order,
                                              kOrderBits<N> * 7 - nr.order_shift, mask, unused_t,
                                              stack + sp) - 1);
          ref = stack[sp];
          prefetch_ref(nodes, blocks, ref);
          continue;
        }
      }
      if constexpr (N >= 8) {
        const unsigned rest = mask & (mask - 1);
        const std::uint32_t a = node.child[std::countr_zero(mask)];
        if (rest && !(rest & (rest - 1)) && (a & node.child[std::countr_zero(rest)] & kLeaf)) {
          // Two leaves: their first blocks in one 8-wide pass, as the closest-hit walk does.
          const std::uint32_t b = node.child[std::countr_zero(rest)];
          const TriangleBlock* ba = blocks + (a & ~kLeaf);
          const TriangleBlock* bb = blocks + (b & ~kLeaf);
          local.blocks(2);
          const PairHits ph =
              test.pair_hits(*ba, *bb, PairLanes<N>::broadcast(t_min),
                             PairLanes<N>::broadcast(t_below));
          for (unsigned m = ph.mask; m; m &= m - 1) {
            const int l = std::countr_zero(m);
            if (on_hit((l < 4 ? ba : bb)->prim_of(l & 3), ph.t[l])) {
              stopped = true;
              goto done;
            }
          }
          // A leaf of more blocks: the rest of it, as a leaf of its own, later.
          if (!ba->last()) stack[sp++] = a + 1;
          if (!bb->last()) stack[sp++] = b + 1;
          goto pop;
        }
      }
      ref = node.child[std::countr_zero(mask)];
      prefetch_ref(nodes, blocks, ref);
      for (mask &= mask - 1; mask; mask &= mask - 1) {
        stack[sp++] = node.child[std::countr_zero(mask)];
        prefetch_ref(nodes, blocks, stack[sp - 1]);
      }
    }
    for (const TriangleBlock* b = blocks + (ref & ~kLeaf);; ++b) {
      local.blocks(1);
      const BlockHits bh = test(*b, t_min_4, t_below_4);
      for (unsigned m = bh.mask; m; m &= m - 1) {
        const int l = std::countr_zero(m);
        if (on_hit(b->prim_of(l), bh.t[l])) {
          stopped = true;
          goto done;
        }
      }
      if (b->last()) break;
    }
  pop:
    if (sp == 0) goto done;
    ref = stack[--sp];
  }
done:
  local.add_to(counts);
  return stopped;
}

template <int N, class Test, class OnHit>
MLIB_INLINE bool any_triangle(const WideBvh<N>& bvh, const TriangleBlock* blocks, const Ray& ray,
                              const Test& test, float t_min, float t_max, OnHit&& on_hit,
                              TraversalCounts* counts) {
  if (bvh.root == kNoChild) return false;
  const RayPre pre(ray);
  return with_walk_nodes(bvh, [&](const auto* nodes) {
    return with_walk_form(ray, pre, counts, [&](auto finite, auto count) {
      return any_triangle_walk<N, Test, decltype(finite)::value, decltype(count)::value>(
          bvh, nodes, blocks, ray, pre, test, t_min, t_max, on_hit, counts);
    });
  });
}

}  // namespace rt2::RT2_ISA
