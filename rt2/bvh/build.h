// rt2/bvh/build.h — the recursive BVH builder (thesis 4.3.1, plus a binned SAH split).
//
// Input: one bounding box per primitive; output: plain data (bvh/node.h). The builder knows
// nothing of triangles or spheres, and nothing of how the tree will be traversed.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#include "rt2/geometry/aabb.h"
#include "rt2/bvh/node.h"

namespace rt2 {

// Builds the tree over `boxes` (finite, non-empty boxes; primitive i has box i).
// Rule (thesis): a node with <= config.max_leaf_size primitives is a leaf, any bigger node
// is split in two. A split that would leave a side empty (coincident centroids) falls back
// to the object median, and so does every split below depth 64, so the depth stays below
// kMaxBvhDepth for any input. Throws rt2::Error for max_leaf_size 0 or sah_bins < 2.
// The tree's node array keeps the capacity the build reserved (two nodes per primitive):
// a caller that keeps the tree shrinks it (`nodes.shrink_to_fit()`), one that only reads it
// once (collapse_bvh) saves the copy.
Bvh build_bvh(const std::vector<Aabb>& boxes, const BvhConfig& config);

// What a tree node's box adds on each side of the span [lo, hi] of its primitives along an
// axis: 4 ulps of the coordinates. The triangle test rounds too, and may accept a ray that
// passes a fraction of an ulp outside a triangle (a grazing ray along a box edge); the box
// around it must not reject what the test inside would accept.
inline float box_pad(float lo, float hi) {
  return std::max(std::fabs(lo), std::fabs(hi)) * 0x1p-21f + std::numeric_limits<float>::min();
}

// The same over `count` primitives, primitive i having the box box_of(i): without a vector
// of boxes, for a large mesh 32 bytes per triangle that need not be written and read again.
// From 2^18 primitives on, box_of is called by several threads at once.
Bvh build_bvh(std::uint32_t count, const std::function<Aabb(std::uint32_t)>& box_of,
              const BvhConfig& config);

}  // namespace rt2
