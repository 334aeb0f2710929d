// rt2/bvh/linear_build.h — a binary BVH from sorted Morton codes (a linear BVH: Lauterbach
// et al. 2009, Karras 2012), for the top level of the two-level tree, rebuilt every frame.
//
// The boxes' centres are ordered along the Z-curve (rt2/lights/morton.h, radix sorted), and
// each node over a run of them splits where the run's highest differing code bit changes
// (at the middle of a run of equal codes). One primitive a leaf: a tree of n leaves has
// 2n - 1 nodes, laid out depth first (a node's first child follows it; BvhNode::offset names
// the second), so subtrees are built in parallel into places known in advance. Its SAH
// cost is higher than build_bvh's; it takes a few nanoseconds a primitive.
#pragma once

#include <vector>

#include "rt2/bvh/node.h"
#include "rt2/geometry/aabb.h"

namespace rt2 {

// The tree over `boxes` (finite, non-empty) into `bvh`, with `threads` OpenMP threads (<= 0:
// all), reusing the storage of the tree it held (a rebuild every frame allocates nothing
// once it has grown).
void build_linear_bvh(const std::vector<Aabb>& boxes, int threads, Bvh& bvh);

}  // namespace rt2
