// rt2/bvh/node.h — the flat BVH the builder produces and the traverser reads.
//
// Plain data, no pointers: nodes in depth-first order (an inner node's first child is the
// next node; its second child's index is stored), leaves referring to a contiguous range
// of `order`, the permutation of the primitives. Wider layouts (4/8-child nodes) are meant
// to be converted from this one.
#pragma once

#include <cstdint>
#include <vector>

#include "mlib/huge_pages.h"

namespace rt2 {

// 32 bytes, two per cache line: bounds as two float triples, each followed by a 32-bit
// field so that a 16-byte load reads bounds plus one field (the traverser masks it out).
// The bounds are padded by 4 ulps of their coordinates (see build.cpp).
struct BvhNode {
  float lo[3];
  std::uint32_t offset;  // leaf: first index into Bvh::order; inner: index of second child
  float hi[3];
  std::uint32_t count;  // leaf: number of primitives (> 0); inner: 0
  bool is_leaf() const { return count > 0; }
};
static_assert(sizeof(BvhNode) == 32);

enum class Split { midpoint, sah };

// The wide tree's nodes (BvhConfig::nodes).
enum class NodeLayout { plain, quantized };

// The builder's knobs.
struct BvhConfig {
  // A node with at most this many primitives becomes a leaf; any bigger node is split
  // (the thesis's rule; 1 ... 16384 and more all work).
  std::uint32_t max_leaf_size = 4;
  // midpoint: the middle of the longest axis of the centroid bounds (the thesis);
  // sah: the best of `sah_bins` planes per axis by the surface area heuristic.
  Split split = Split::sah;
  int sah_bins = 16;
  // The SAH counts a leaf's primitives in blocks of this many (a power of two, 1 ... 64,
  // default 4): leaves are
  // tested a TriangleBlock (4 triangles) at a time, so a split into 4 + 4 costs less than
  // one into 3 + 5, and leaves come out fuller (Embree's rule). 1 is the plain SAH.
  std::uint32_t sah_block = 4;
  // The wide tree's nodes (bvh/wide_bvh.h): float boxes, or boxes quantized to 8 bits
  // (about 10 % fewer bytes per triangle, and slower rays: docs/performance.md).
  NodeLayout nodes = NodeLayout::plain;
};

struct BvhStats {
  double build_ms = 0.0;
  std::uint32_t nodes = 0;
  std::uint32_t leaves = 0;
  std::uint32_t max_depth = 0;  // root = 0
  std::uint32_t max_leaf_prims = 0;
};

struct Bvh {
  // Empty when there are no primitives. On huge pages once large (mlib/huge_pages.h): the
  // builder reserves two nodes per primitive and uses fewer than one, and fresh memory
  // is cheaper to fill in 2 MiB pages.
  mlib::HugePageVector<BvhNode> nodes;
  std::vector<std::uint32_t> order;  // primitive indices in leaf order
  BvhStats stats;
};

// Depth never exceeds this (the builder switches to median splits before it): the
// traversal stack is a fixed array of this size.
inline constexpr std::uint32_t kMaxBvhDepth = 100;

}  // namespace rt2
