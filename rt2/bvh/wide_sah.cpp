// rt2/bvh/wide_sah.cpp — the wide tree's surface area cost in Embree's terms (wide_bvh.h).
#include "rt2/bvh/wide_bvh.h"

namespace rt2 {

namespace {

// Half the surface area of the box [lo, hi], in double (the float box's extents exactly).
double half_area(const float (&lo)[3], const float (&hi)[3]) {
  const double x = double(hi[0]) - lo[0], y = double(hi[1]) - lo[1], z = double(hi[2]) - lo[2];
  return x * y + y * z + z * x;
}

// Half the surface area of slot i's box (as the walks decode it).
template <class Node>
double half_area(const Node& node, int i) {
  const Aabb b = node.box(i);
  return half_area({b.lo[0], b.lo[1], b.lo[2]}, {b.hi[0], b.hi[1], b.hi[2]});
}

std::uint32_t leaf_blocks(const TriangleBlock* first) {
  std::uint32_t n = 1;
  for (const TriangleBlock* b = first; !b->last(); ++b) ++n;
  return n;
}

}  // namespace

template <int N>
WideSah wide_sah(const WideBvh<N>& bvh, const TriangleBlock* blocks) {
  WideSah sah;
  if (bvh.root == kNoChild) return sah;
  if (bvh.root & kLeaf) {
    sah.leaves = leaf_blocks(blocks + (bvh.root & ~kLeaf));
    return sah;
  }
  bvh.with_nodes([&](const auto* nodes) {
    // The root's box: the union of its children's.
    Aabb root;
    for (int i = 0; i < nodes[0].slots(); ++i) root.grow(nodes[0].box(i));
    const double root_area =
        half_area({root.lo[0], root.lo[1], root.lo[2]}, {root.hi[0], root.hi[1], root.hi[2]});
    if (!(root_area > 0.0)) return;  // a flat or degenerate scene: no ratio to state
    sah.nodes = 1.0;
    for (std::size_t k = 0; k < bvh.node_count(); ++k)
      for (int i = 0; i < nodes[k].slots(); ++i) {
        const std::uint32_t c = nodes[k].child[i];
        const double ratio = half_area(nodes[k], i) / root_area;
        if (c & kLeaf)
          sah.leaves += ratio * leaf_blocks(blocks + (c & ~kLeaf));
        else
          sah.nodes += ratio;
      }
  });
  return sah;
}

template WideSah wide_sah<4>(const WideBvh<4>&, const TriangleBlock*);
template WideSah wide_sah<8>(const WideBvh<8>&, const TriangleBlock*);
template WideSah wide_sah<16>(const WideBvh<16>&, const TriangleBlock*);

}  // namespace rt2
