// rt2/lights/cluster_visibility.h — shadow rays that need not be traced: a light that every point
// of a cluster of hits provably sees.
//
// The ray-traced, exact form of the fully lit shadow tile of the tiled-shadows text
// (../shared/reference/tiled-shadows.txt): a shadow ray from a point of box B to a light at
// L stays inside the box H = B ∪ {L}. When no triangle or sphere has a bounding box that
// meets H (each padded by 2^-12 of its own coordinates, well beyond any ray test's
// rounding), and no plane separates B from L (all of B's corners and L strictly on one
// side, with a margin), the transmittance of every such ray is exactly 1 and it is not
// traced. Otherwise nothing is claimed and the rays are traced as usual.
#pragma once

#include <cstddef>
#include <vector>

#include "rt2/geometry/aabb.h"
#include "rt2/bvh/accel.h"

namespace rt2 {

// gather() collects, once per cluster, the triangles and spheres near it (the region its
// lights' rays can reach); sees() then tests one light against those few. A primitive is
// out of the way when its box misses the hull's cover — the boxes of the hull's slices
// (1 - t) B + t L for t in [i/4, (i+1)/4], which hold every ray's points at those t — or,
// for a triangle, when all of the hull's corners (B's 8 and L) lie strictly on one side of
// its plane (the face a cluster of hits lies on, lit from the front, is out of the way).
// A cluster with more than kMaxOccluders primitives nearby proves nothing.
class ClusterVisibility {
 public:
  static constexpr std::size_t kMaxOccluders = 64;
  struct Occluder {
    Aabb box;
    vec4 plane;    // a triangle's n.xyz, d (n·x + d = 0 on it); zero for a sphere
    float margin;  // the largest |n·x| + |d| over the triangle (its side test's scale); < 0: none
  };

  // For shadow rays from points of `cluster` to lights inside `reach` (a box holding
  // `cluster` and the lights).
  void gather(const Accel& accel, const Aabb& cluster, const Aabb& reach);
  // Whether every shadow ray from a point of the cluster to a light at `light` (inside the
  // `reach` of gather) provably meets no geometry.
  bool sees(const vec4& light) const;

 private:
  bool separated_by(const vec4& plane, float scale, const vec4& light) const;

  Aabb cluster_;
  bool complete_ = false;             // every occluder near the cluster is in occluders_
  std::vector<Occluder> occluders_;   // the triangles and spheres whose boxes meet reach
  std::vector<vec4> planes_;          // n.xyz, d: planes with the whole cluster on one side,
                                      // oriented so that side is positive
  std::vector<float> plane_margin_;   // per plane, the margin a light needs beyond it
};

}  // namespace rt2
