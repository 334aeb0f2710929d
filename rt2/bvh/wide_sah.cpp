// rt2/bvh/wide_sah.cpp — the wide tree's surface area cost in Embree's terms (wide_bvh.h).
#include <algorithm>

#include "rt2/bvh/wide_bvh.h"

namespace rt2 {

namespace {

// Half the surface area of the box [lo, hi], in double (the float box's extents exactly).
double half_area(const float (&lo)[3], const float (&hi)[3]) {
  const double x = double(hi[0]) - lo[0], y = double(hi[1]) - lo[1], z = double(hi[2]) - lo[2];
  return x * y + y * z + z * x;
}

// Half the surface area of slot i's box.
template <int N>
double half_area(const WideNode<N>& node, int i) {
  return half_area({node.bounds[0][i], node.bounds[2][i], node.bounds[4][i]},
                   {node.bounds[1][i], node.bounds[3][i], node.bounds[5][i]});
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
  float lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    lo[a] = *std::min_element(root.bounds[2 * a], root.bounds[2 * a] + N);
    hi[a] = *std::max_element(root.bounds[2 * a + 1], root.bounds[2 * a + 1] + N);
  }
  const double root_area = half_area(lo, hi);
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
template WideSah wide_sah<16>(const WideBvh<16>&, const TriangleBlock*);

}  // namespace rt2
