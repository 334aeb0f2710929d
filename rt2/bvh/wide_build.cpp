// rt2/bvh/wide_build.cpp — collapsing the binary tree into the wide one (see wide_bvh.h).
#include <algorithm>
#include <limits>

#include "rt2/bvh/wide_bvh.h"

namespace rt2 {

namespace {

template <int N>
class Collapser {
 public:
  Collapser(const Bvh& bvh, const std::vector<Triangle>& tris, std::vector<TriangleBlock>& blocks,
            WideBvh<N>& out)
      : bvh_(bvh), tris_(tris), blocks_(blocks), out_(out) {}

  // The reference for the root: a wide node made from it (nodes[0]), or its leaf.
  std::uint32_t convert_root() {
    if (bvh_.nodes[0].is_leaf()) return leaf(bvh_.nodes[0]);
    out_.nodes.emplace_back();
    fill(0, 0, 0);
    return 0;
  }

 private:
  // Fills wide node `index` from binary node b (inner). The node's inner children get
  // consecutive slots, allocated before any of their subtrees, so siblings sit side by
  // side in memory (as Embree's allocator places them): a walk that returns to a sibling
  // finds it near the one it just left. Leaves' blocks likewise follow each other.
  void fill(std::uint32_t index, std::uint32_t b, std::uint32_t depth) {
    out_.max_depth = std::max(out_.max_depth, depth);
    const BvhNode& node = bvh_.nodes[b];
    // Open the largest inner child until there are N children (or only leaves).
    std::uint32_t kids[N] = {b + 1, node.offset};
    int n = 2;
    while (n < N) {
      int best = -1;
      float best_area = -1.0f;
      for (int i = 0; i < n; ++i) {
        const BvhNode& k = bvh_.nodes[kids[i]];
        if (k.is_leaf()) continue;
        const float a = area(k);
        if (a > best_area) {
          best_area = a;
          best = i;
        }
      }
      if (best < 0) break;
      const std::uint32_t opened = kids[best];
      kids[best] = opened + 1;
      kids[n++] = bvh_.nodes[opened].offset;
    }
    WideNode<N> w;
    for (int i = 0; i < N; ++i) {
      for (int a = 0; a < 3; ++a) {
        w.bounds[2 * a][i] = std::numeric_limits<float>::infinity();
        w.bounds[2 * a + 1][i] = -std::numeric_limits<float>::infinity();
      }
      w.child[i] = 0;
    }
    for (int i = 0; i < n; ++i) {
      const BvhNode& k = bvh_.nodes[kids[i]];
      for (int a = 0; a < 3; ++a) {
        w.bounds[2 * a][i] = k.lo[a];
        w.bounds[2 * a + 1][i] = k.hi[a];
      }
      if (k.is_leaf()) {
        w.child[i] = leaf(k);
      } else {
        w.child[i] = static_cast<std::uint32_t>(out_.nodes.size());
        out_.nodes.emplace_back();
      }
    }
    set_octant_orders(w, n);
    out_.nodes[index] = w;
    for (int i = 0; i < n; ++i)
      if (!(w.child[i] & kLeaf)) fill(w.child[i], kids[i], depth + 1);
  }

  // WideNode::octant_order for the n children in slots [0, n). Each child's position is
  // its rank, counted without a branch (a sort of eight random keys mispredicts about every
  // other comparison). Octant 7 - o is octant o's order reversed (its diagonal is the
  // opposite one). A node of two children keeps the identity order: the walk orders two
  // children by their distances (wide_traverse.h).
  static void set_octant_orders(WideNode<N>& w, int n) {
    for (int j = 0; j < N; ++j) w.octant_order[j] = std::uint32_t(j) * 0x249249u;  // j in each field
    if (n <= 2) return;
    for (int j = 0; j < N; ++j) w.octant_order[j] = 0;
    float centre[3][N];  // halves added: lo + hi could overflow to inf (and a key to NaN)
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < n; ++i)
        centre[a][i] = w.bounds[2 * a][i] * 0.5f + w.bounds[2 * a + 1][i] * 0.5f;
    for (int o = 0; o < 4; ++o) {
      float key[N];  // along the diagonal: farther is larger
      for (int i = 0; i < n; ++i)
        key[i] = ((o & 1 ? -centre[0][i] : centre[0][i]) + (o & 2 ? -centre[1][i] : centre[1][i])) +
                 (o & 4 ? -centre[2][i] : centre[2][i]);
      std::uint32_t slot_at[N];
      for (int j = 0; j < N; ++j) slot_at[j] = std::uint32_t(j);  // the unused slots stay last
      for (int i = 0; i < n; ++i) {
        int rank = 0;  // the keys before key i: larger, or equal in a lower slot
        for (int j = 0; j < n; ++j) rank += (key[j] > key[i]) | ((key[j] == key[i]) & (j < i));
        slot_at[rank] = std::uint32_t(i);
      }
      for (int j = 0; j < N; ++j) {
        const std::uint32_t backward = j < n ? slot_at[n - 1 - j] : slot_at[j];
        w.octant_order[j] |= slot_at[j] << (3 * o) | backward << (3 * (7 - o));
      }
    }
  }

  static float area(const BvhNode& k) {
    const float x = k.hi[0] - k.lo[0], y = k.hi[1] - k.lo[1], z = k.hi[2] - k.lo[2];
    return x * y + y * z + z * x;
  }

  std::uint32_t leaf(const BvhNode& node) {
    ++out_.leaves;
    const auto first = static_cast<std::uint32_t>(blocks_.size());
    for (std::uint32_t i = 0; i < node.count; i += TriangleBlock::kLanes) {
      TriangleBlock block = TriangleBlock::empty();
      for (std::uint32_t l = 0; l < TriangleBlock::kLanes && i + l < node.count; ++l) {
        const std::uint32_t t = node.offset + i + l;
        block.set(static_cast<int>(l), tris_[t], t);
      }
      blocks_.push_back(block);
    }
    blocks_.back().prim[0] |= TriangleBlock::kLastBlock;
    return kLeaf | first;
  }

  const Bvh& bvh_;
  const std::vector<Triangle>& tris_;
  std::vector<TriangleBlock>& blocks_;
  WideBvh<N>& out_;
};

}  // namespace

template <int N>
WideBvh<N> collapse_bvh(const Bvh& bvh, const std::vector<Triangle>& triangles,
                        std::vector<TriangleBlock>& blocks) {
  WideBvh<N> out;
  if (bvh.nodes.empty()) return out;
  out.nodes.reserve(bvh.nodes.size() / (N - 1) + 1);
  Collapser<N> c(bvh, triangles, blocks, out);
  out.root = c.convert_root();
  out.nodes.shrink_to_fit();
  return out;
}

template WideBvh<4> collapse_bvh<4>(const Bvh&, const std::vector<Triangle>&,
                                    std::vector<TriangleBlock>&);
template WideBvh<8> collapse_bvh<8>(const Bvh&, const std::vector<Triangle>&,
                                    std::vector<TriangleBlock>&);

}  // namespace rt2
