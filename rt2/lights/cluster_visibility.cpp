// rt2/lights/cluster_visibility.cpp — see cluster_visibility.h.
#include "rt2/lights/cluster_visibility.h"

#include <algorithm>
#include <cmath>

namespace rt2 {
namespace {

// Far more than the rounding of a ray's walk (a few 2^-24 of the coordinates): boxes are
// compared padded by 2^-12 of the magnitudes involved.
constexpr float kBoxPad = 0x1p-12f;
// A plane's signed distance is computed to a few 2^-24 of |x|·|n| + |d|; 2^-20 is the margin.
constexpr float kPlanePad = 0x1p-20f;

bool overlap(const Aabb& a, const Aabb& b) {
  return a.lo[0] <= b.hi[0] && b.lo[0] <= a.hi[0] && a.lo[1] <= b.hi[1] && b.lo[1] <= a.hi[1] &&
         a.lo[2] <= b.hi[2] && b.lo[2] <= a.hi[2];
}

// `b` widened by 2^-12 of its largest coordinate magnitude. Both the hull and each
// occluder are widened by their own: a ray test's rounding grows with the primitive's
// coordinates (a triangle's edges, a sphere's c = |o - c|^2 - r^2) as well as the ray's.
Aabb padded(const Aabb& b) {
  float m = 0.0f;
  for (int a = 0; a < 3; ++a) m = std::max({m, std::fabs(b.lo[a]), std::fabs(b.hi[a])});
  const vec4 pad(m * kBoxPad, m * kBoxPad, m * kBoxPad);
  Aabb out;
  out.lo = b.lo - pad;
  out.hi = b.hi + pad;
  return out;
}

// The largest |n·x| + |d| over the box (the magnitude a plane's side test rounds against).
float plane_scale(const vec4& n, float d, const Aabb& b) {
  float s = std::fabs(d);
  for (int a = 0; a < 3; ++a) s += std::fabs(n[a]) * std::max(std::fabs(b.lo[a]), std::fabs(b.hi[a]));
  return s;
}

// The hull of the cluster and a light is split into this many slices along the rays.
constexpr int kSlices = 4;
// A triangle's plane is evaluated to a few 2^-24 of |n|·|x| + |d|: 2^-19 is the margin
// (small beside the 2^-15 relative offset that lifts shadow-ray origins off a surface).
constexpr float kTrianglePlanePad = 0x1p-19f;

// Appends the triangles of the wide tree whose padded boxes meet `region`; false once more
// than `limit` are found. Node boxes are padded by their own magnitude, which is at least
// that of any triangle below them, so no triangle whose padded box meets `region` is missed.
template <int N>
bool triangle_boxes(const Accel& acc, const Aabb& region, std::size_t limit,
                    std::vector<ClusterVisibility::Occluder>& out) {
  const WideBvh<N>& bvh = acc.wide<N>();
  if (bvh.root == kNoChild) return true;
  std::uint32_t stack[256];
  int top = 0;
  stack[top++] = bvh.root;
  while (top > 0) {
    const std::uint32_t ref = stack[--top];
    if (ref & kLeaf) {
      for (const TriangleBlock* b = acc.blocks.data() + (ref & ~kLeaf);; ++b) {
        for (int l = 0; l < TriangleBlock::kLanes; ++l) {
          const std::uint32_t prim = b->prim_of(l);
          if (prim == TriangleBlock::kNoPrim) continue;
          const Triangle& t = acc.tris[prim];
          Aabb tight;
          tight.grow(t.v0);
          tight.grow(t.v1);
          tight.grow(t.v2);
          const Aabb box = padded(tight);
          if (!overlap(box, region)) continue;
          if (out.size() == limit) return false;
          const vec4 n = t.n;
          const float d = -(n[0] * t.v0[0] + n[1] * t.v0[1] + n[2] * t.v0[2]);
          out.push_back({box, vec4(n[0], n[1], n[2], d), plane_scale(n, d, tight)});
        }
        if (b->last()) break;
      }
      continue;
    }
    const bool deeper = bvh.with_nodes([&](const auto* nodes) {
      const auto& node = nodes[ref];
      for (int c = 0; c < node.slots(); ++c) {
        if (!overlap(padded(node.box(c)), region)) continue;
        if (top == 256) return true;
        stack[top++] = node.child[c];
      }
      return false;
    });
    if (deeper) return false;  // deeper than any tree rt2 builds: prove nothing
  }
  return true;
}

// Appends the spheres whose padded boxes meet `region`, walking the spheres' binary tree
// (nodes padded as in triangle_boxes); false once more than `limit` are found.
bool sphere_boxes(const Accel& acc, const Aabb& region, std::size_t limit,
                  std::vector<ClusterVisibility::Occluder>& out) {
  if (acc.spheres.empty()) return true;
  const auto& nodes = acc.sphere_bvh.nodes;
  std::uint32_t stack[kMaxBvhDepth + 1];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const BvhNode& n = nodes[stack[--top]];
    Aabb node;
    node.lo = vec4(n.lo[0], n.lo[1], n.lo[2]);
    node.hi = vec4(n.hi[0], n.hi[1], n.hi[2]);
    if (!overlap(padded(node), region)) continue;
    if (!n.is_leaf()) {
      stack[top++] = static_cast<std::uint32_t>(&n - nodes.data()) + 1;  // first child
      stack[top++] = n.offset;                                           // second child
      continue;
    }
    for (std::uint32_t i = n.offset; i < n.offset + n.count; ++i) {
      const Sphere& s = acc.spheres[i];
      const vec4 r(s.radius, s.radius, s.radius);
      Aabb tight;
      tight.lo = s.center - r;
      tight.hi = s.center + r;
      const Aabb box = padded(tight);
      if (!overlap(box, region)) continue;
      if (out.size() == limit) return false;
      out.push_back({box, vec4(0.0f, 0.0f, 0.0f, 0.0f), -1.0f});
    }
  }
  return true;
}

}  // namespace

void ClusterVisibility::gather(const Accel& accel, const Aabb& cluster, const Aabb& reach) {
  cluster_ = cluster;
  occluders_.clear();
  planes_.clear();
  plane_margin_.clear();
  const Aabb region = padded(reach);
  const auto triangles = [&](auto width) {  // the tree of the width accel's ISA traces
    return triangle_boxes<decltype(width)::value>(accel, region, kMaxOccluders, occluders_);
  };
  // An instance's triangles are not gathered: one whose box meets the region proves nothing.
  const auto no_instance = [&] {
    if (accel.instances.empty()) return true;
    const BvhNode& root = accel.instance_bvh.nodes[0];
    Aabb box;
    box.lo = vec4(root.lo[0], root.lo[1], root.lo[2]);
    box.hi = vec4(root.hi[0], root.hi[1], root.hi[2]);
    return !overlap(padded(box), region);
  };
  complete_ = !cluster.is_empty() && no_instance() && with_bvh_width(accel.isa, triangles) &&
              sphere_boxes(accel, region, kMaxOccluders, occluders_);
  if (!complete_) return;
  // Planes: the cluster's 8 corners strictly on one side (with the margin), or no claim.
  for (const Plane& pl : accel.planes) {
    float lo = kInfinity, hi = -kInfinity, scale = std::fabs(pl.d), reach_scale = 0.0f;
    for (int corner = 0; corner < 8; ++corner) {
      const vec4 x((corner & 1) ? cluster.hi[0] : cluster.lo[0],
                   (corner & 2) ? cluster.hi[1] : cluster.lo[1],
                   (corner & 4) ? cluster.hi[2] : cluster.lo[2]);
      const float s = float(dot(x, pl.n)) + pl.d;
      lo = std::min(lo, s);
      hi = std::max(hi, s);
      scale = std::max(scale, std::fabs(x[0] * pl.n[0]) + std::fabs(x[1] * pl.n[1]) +
                                  std::fabs(x[2] * pl.n[2]) + std::fabs(pl.d));
    }
    for (int corner = 0; corner < 8; ++corner) {  // where the lights can be
      const vec4 x((corner & 1) ? reach.hi[0] : reach.lo[0], (corner & 2) ? reach.hi[1] : reach.lo[1],
                   (corner & 4) ? reach.hi[2] : reach.lo[2]);
      reach_scale = std::max(reach_scale, std::fabs(x[0] * pl.n[0]) + std::fabs(x[1] * pl.n[1]) +
                                              std::fabs(x[2] * pl.n[2]) + std::fabs(pl.d));
    }
    const float margin = kPlanePad * scale;
    if (lo > margin) {
      planes_.push_back(vec4(pl.n[0], pl.n[1], pl.n[2], pl.d));
    } else if (hi < -margin) {
      planes_.push_back(vec4(-pl.n[0], -pl.n[1], -pl.n[2], -pl.d));
    } else {
      complete_ = false;  // the cluster touches the plane: rays may cross it
      return;
    }
    // A light must be beyond the margin too, with room for the distance along the ray.
    plane_margin_.push_back(kPlanePad * (reach_scale + std::max(std::fabs(lo), std::fabs(hi))));
  }
}

bool ClusterVisibility::sees(const vec4& light) const {
  if (!complete_) return false;
  for (std::size_t i = 0; i < planes_.size(); ++i) {
    const vec4& p = planes_[i];
    const float s = light[0] * p[0] + light[1] * p[1] + light[2] * p[2] + p[3];
    if (!(s > plane_margin_[i])) return false;
  }
  Aabb hull = cluster_;
  hull.grow(light);
  const Aabb h = padded(hull);
  // The cover of the hull: slice i holds the rays' points for t in [i, i + 1] / kSlices.
  Aabb slices[kSlices];
  for (int i = 0; i < kSlices; ++i) {
    Aabb slice;
    for (const float t : {float(i) / kSlices, float(i + 1) / kSlices}) {
      slice.grow((1.0f - t) * cluster_.lo + t * light);
      slice.grow((1.0f - t) * cluster_.hi + t * light);
    }
    slices[i] = padded(slice);
  }
  for (const Occluder& o : occluders_) {
    if (!overlap(o.box, h)) continue;
    bool met = false;
    for (const Aabb& slice : slices) met = met || overlap(o.box, slice);
    if (!met) continue;
    if (o.margin >= 0.0f && separated_by(o.plane, o.margin, light)) continue;
    return false;
  }
  return true;
}

// Whether the hull's corners (the cluster's 8 and the light) all lie on one side of the
// plane p (n·x + d), each beyond 2^-19 of the larger of the magnitudes its side test and
// the triangle's own (`scale`) round against.
bool ClusterVisibility::separated_by(const vec4& p, float scale, const vec4& light) const {
  int above = 0, below = 0;
  for (int corner = 0; corner < 9; ++corner) {
    const vec4 x = corner == 8 ? light
                               : vec4((corner & 1) ? cluster_.hi[0] : cluster_.lo[0],
                                      (corner & 2) ? cluster_.hi[1] : cluster_.lo[1],
                                      (corner & 4) ? cluster_.hi[2] : cluster_.lo[2]);
    const float s = p[0] * x[0] + p[1] * x[1] + p[2] * x[2] + p[3];
    const float m = kTrianglePlanePad * std::max(scale, std::fabs(p[0] * x[0]) +
                                                            std::fabs(p[1] * x[1]) +
                                                            std::fabs(p[2] * x[2]) +
                                                            std::fabs(p[3]));
    above += s > m;
    below += s < -m;
  }
  return above == 9 || below == 9;
}

}  // namespace rt2
