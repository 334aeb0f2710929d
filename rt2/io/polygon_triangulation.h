// rt2/io/polygon_triangulation.h — an OBJ face of any number of corners into triangles
// (internal: part of rt2/io/scene_io.h's implementation, called by rt2/io/obj_mesh.cpp).
//
// Quads are split along a diagonal (the shorter one, as tinyobjloader does, unless only the
// other one lies inside: a concave quad). Larger polygons are ear-clipped in their own plane:
// the Newell normal picks the axis plane they are projected onto, and a bounding volume
// hierarchy over the reflex corners makes each ear test look only at corners near the ear.
// Concave polygons and polygons with holes joined by a bridge edge (walked twice, its ends
// repeated, as LightWave and 3ds Max write them) are triangulated exactly; self-intersecting
// and degenerate ones end, after bounded work, in a fan over the corners left; none hangs.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "rt2/geometry/ray.h"

namespace rt2::io {

using CornerTriangle = std::array<std::uint32_t, 3>;  // indices into the polygon's corners

// Why not CGAL (libcgal-dev: its constrained Delaunay triangulation is header-only): it pulls
// Boost, GMP and MPFR into the build (libcgal-dev depends on them) and heavy templates into
// every build mode, and its triangulation packages are GPL-3, which rt2 would inherit. It
// also works on points, not on a polygon's corners: it merges the two copies of each bridge
// end (each triangle corner would then have to be mapped back to one of the face's corners,
// with its own normal), and the usual inside/outside marking by crossing constrained edges
// breaks on a bridge, which has the inside on both sides, unless edges walked twice are
// dropped first; a self-intersecting face becomes new vertices at the crossings. This ear
// clipper is a few hundred tested lines that work on the corners as written, keep the
// face's winding, create no vertex, run in about n log n and fail in a way we choose.
//
// Triangulates polygons one after the other, reusing its buffers (no allocation per polygon
// once they have grown).
class PolygonTriangulator {
 public:
  // Appends the triangles of the polygon whose corners, in order, are `corners` (positions;
  // w ignored) to `out`: n − 2 of them for n >= 3 corners (none for fewer), each with the
  // polygon's winding, as indices into `corners`. Some may be degenerate (zero area: at
  // repeated or collinear corners), for the caller to drop and count. Returns false when ear
  // clipping could not finish — a self-intersecting or degenerate polygon, non-finite
  // coordinates, or more work than a simple polygon of this size needs — and the corners
  // left were triangulated as a fan.
  bool triangulate(std::span<const vec4> corners, std::vector<CornerTriangle>& out);

  // Work units (tree nodes and corners looked at) of the last polygon: 3 to 10 n log2 n for
  // simple polygons of n corners (tested). Past budget(n), ear clipping gives up.
  std::size_t last_work() const { return work_; }
  static std::size_t budget(std::size_t corners);

 private:
  bool triangulate_quad(std::span<const vec4> corners, std::vector<CornerTriangle>& out);
  bool ear_clip(std::span<const vec4> corners, std::vector<CornerTriangle>& out);
  bool project(std::span<const vec4> corners);
  void update(std::uint32_t v);
  bool is_ear(std::uint32_t b, bool strict);
  bool blocks(std::uint32_t p, std::uint32_t a, std::uint32_t b, std::uint32_t c,
              bool strict) const;
  void clip(std::uint32_t b, std::vector<CornerTriangle>& out);
  bool clip_zero_area(std::uint32_t& start, std::vector<CornerTriangle>& out);
  bool clip_relaxed_ear(std::uint32_t& start, std::vector<CornerTriangle>& out);
  double turn(std::uint32_t a, std::uint32_t b, std::uint32_t c) const;

  // The polygon as a ring of corners in 2D (counter-clockwise), and which are still in it.
  std::vector<double> x_, y_;
  std::vector<std::uint32_t> prev_, next_;
  std::vector<std::uint8_t> alive_, reflex_, in_tree_;
  std::vector<std::uint32_t> pending_;  // corners beside recent cuts, to try first
  std::size_t left_ = 0;                // corners still in the ring

  // The reflex (or flat) corners at the last build_tree, in Morton order: leaf k holds
  // tree_items_[k * kLeaf ..], its box is boxes_[k]; level l's boxes start at
  // level_start_[l], node k covering nodes 2k and 2k + 1 below. Corners that turn reflex
  // later (only after a zero-area clip) are in late_reflex_.
  struct Box {
    double x0, y0, x1, y1;
  };
  static constexpr std::size_t kLeaf = 4;
  void build_tree(std::uint32_t start);
  bool may_hold(const Box& box, std::uint32_t a, std::uint32_t b, std::uint32_t c) const;
  std::vector<std::uint32_t> tree_items_, late_reflex_;
  std::vector<Box> boxes_;
  std::vector<std::size_t> level_start_;
  std::vector<std::uint64_t> order_;                        // build_tree's sort
  std::vector<std::pair<std::size_t, std::size_t>> stack_;  // is_ear's (level, node)
  std::size_t reflex_count_ = 0;                            // alive reflex corners
  std::size_t built_reflex_ = 0;                            // reflex corners at the last build

  std::size_t work_ = 0, budget_ = 0;
};

}  // namespace rt2::io
