// rt2/bvh/wide_sah.cpp — the wide tree's surface area cost in Embree's terms (wide_bvh.h).
#include <algorithm>
#include <limits>

#include "rt2/bvh/wide_bvh.h"

namespace rt2 {

namespace {

// Half the surface area of slot i's box, in double (the float box's extents exactly).
template <int N>
double half_area(const WideNode<N>& node, int i) {
  const double x = double(node.bounds[1][i]) - node.bounds[0][i];
  const double y = double(node.bounds[3][i]) - node.bounds[2][i];
  const double z = double(node.bounds[5][i]) - node.bounds[4][i];
  return x * y + y * z + z * x;
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
  // The root's box: the union of its children's (an unused slot's empty box adds nothing).
  const WideNode<N>& root = bvh.nodes[0];
  WideNode<N> box{};
  for (int r = 0; r < 6; ++r) {
    const bool hi = r & 1;
    float v = hi ? -std::numeric_limits<float>::infinity() : std::numeric_limits<float>::infinity();
    for (int i = 0; i < N; ++i) v = hi ? std::max(v, root.bounds[r][i]) : std::min(v, root.bounds[r][i]);
    box.bounds[r][0] = v;
  }
  const double root_area = half_area(box, 0);
  if (!(root_area > 0.0)) return sah;  // a flat or degenerate scene: no ratio to state
  sah.nodes = 1.0;
  for (const WideNode<N>& node : bvh.nodes)
    for (int i = 0; i < N; ++i) {
      const std::uint32_t c = node.child[i];
      if (!(node.bounds[0][i] <= node.bounds[1][i])) continue;  // unused slot
      const double ratio = half_area(node, i) / root_area;
      if (c & kLeaf)
        sah.leaves += ratio * leaf_blocks(blocks + (c & ~kLeaf));
      else
        sah.nodes += ratio;
    }
  return sah;
}

template WideSah wide_sah<4>(const WideBvh<4>&, const TriangleBlock*);
template WideSah wide_sah<8>(const WideBvh<8>&, const TriangleBlock*);

}  // namespace rt2
