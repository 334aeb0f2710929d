// rt2/bvh/traverse.h — walking a BVH (thesis 4.3.2), ordered and with early exit.
//
// The traverser knows boxes, not primitives: at each leaf it calls `leaf(first, count,
// t_max)`, which tests primitives order[first .. first+count) and may shrink t_max (closest
// hit) or return true to stop (any hit). Inner nodes visit the nearer child first and push
// the farther one with its entry distance; a popped node is skipped when its entry lies
// beyond the current closest hit. The stack is a fixed array: the builder bounds the depth.
// (Not a layout holding both children's boxes in the parent for one SIMD pass: slower here
// than these 32-byte nodes.)
#pragma once

#include <utility>

#include "rt2/geometry/aabb.h"
#include "rt2/bvh/node.h"

namespace rt2 {

MLIB_INLINE float node_entry(const BvhNode& n, const RayPre& r, float t_min, float t_max) {
  return slab_entry(mlib::load_xyz(n.lo), mlib::load_xyz(n.hi), r, t_min, t_max);
}

// AnyHit = true: stop as soon as `leaf` returns true. Otherwise `leaf`'s return value is
// ignored and the traversal runs until no node can hold a hit closer than t_max.
template <bool AnyHit, class Leaf>
inline void traverse(const Bvh& bvh, const RayPre& r, float t_min, float& t_max, Leaf&& leaf) {
  if (bvh.nodes.empty()) return;
  const BvhNode* nodes = bvh.nodes.data();
  if (node_entry(nodes[0], r, t_min, t_max) == kInfinity) return;
  struct Entry {
    std::uint32_t node;
    float t;
  };
  Entry stack[kMaxBvhDepth + 1];
  int sp = 0;
  std::uint32_t current = 0;
  for (;;) {
    const BvhNode& n = nodes[current];
    if (!n.is_leaf()) {
      std::uint32_t a = current + 1, b = n.offset;
      float ta = node_entry(nodes[a], r, t_min, t_max);
      float tb = node_entry(nodes[b], r, t_min, t_max);
      if (tb < ta) {
        std::swap(a, b);
        std::swap(ta, tb);
      }
      if (ta != kInfinity) {
        if (tb != kInfinity) stack[sp++] = {b, tb};
        current = a;
        continue;
      }
    } else if (leaf(n.offset, n.count, t_max) && AnyHit) {
      return;
    }
    for (;;) {  // the next pushed node that can still hold a closer hit
      if (sp == 0) return;
      const Entry e = stack[--sp];
      if (e.t <= t_max * kSlabPad) {  // padded like the slab test: no rounding culls a hit
        current = e.node;
        break;
      }
    }
  }
}

}  // namespace rt2
