// rt2/bvh/build.h — the recursive BVH builder (thesis 4.3.1, plus a binned SAH split).
//
// Input: one bounding box per primitive; output: plain data (bvh/node.h). The builder knows
// nothing of triangles or spheres, and nothing of how the tree will be traversed.
#pragma once

#include <vector>

#include "rt2/aabb.h"
#include "rt2/bvh/node.h"

namespace rt2 {

// Builds the tree over `boxes` (finite, non-empty boxes; primitive i has box i).
// Rule (thesis): a node with <= config.max_leaf_size primitives is a leaf, any bigger node
// is split in two. A split that would leave a side empty (coincident centroids) falls back
// to the object median, and so does every split below depth 64, so the depth stays below
// kMaxBvhDepth for any input. Throws rt2::Error for max_leaf_size 0 or sah_bins < 2.
Bvh build_bvh(const std::vector<Aabb>& boxes, const BvhConfig& config);

}  // namespace rt2
