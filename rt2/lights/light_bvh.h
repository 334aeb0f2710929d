// rt2/lights/light_bvh.h — a hierarchy over the lights' spheres of influence, built from sorted
// Morton codes every frame, that finds the lights able to reach a point or a box.
//
// The clustered-lighting text (../shared/reference/clustered-light-bvh.txt, section 3.3)
// builds its light BVH on the GPU each frame: the lights' bounds, a Morton code per light,
// a radix sort, then the tree "from linear runs of the sorted sequence", level by level.
// rt2 does the same on the CPU with OpenMP: the lights in Morton order are taken four at a
// time (the leaves; a walk tests their spheres, centre = position, radius = range), level 0
// holds each group's box, and each entry of level k + 1 boxes four of level k, stored as a
// block of four boxes (structure of arrays, one SIMD test); the top has at most four.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "rt2/geometry/aabb.h"
#include "rt2/scene/light.h"
#include "rt2/scene/light_path.h"

namespace rt2 {

// Queries are conservative: every light whose sphere contains the point (meets the box) is
// returned, and possibly a few more (the spheres are padded by 2^-16 of their radius, far
// more than the rounding of any distance computed in float), so shading applies the exact
// test (rt2/scene/light.h's in_range) and skipping the others changes no pixel. Lights
// without a range are in no tree: every query returns them. Results come in increasing
// light index (scene order), which keeps a point's terms summed in the same order in every
// culling mode.
class LightBvh {
 public:
  // Milliseconds per step of a frame's light update: one pass over the lights (moving
  // them, when they move, their padded spheres and their bounds), the Morton codes (with
  // the list of lights that have a range), the sort, the tree.
  struct BuildTimes {
    double lights_ms = 0.0, morton_ms = 0.0, sort_ms = 0.0, tree_ms = 0.0;
    double total_ms() const { return lights_ms + morton_ms + sort_ms + tree_ms; }
  };

  // Builds over `lights` (positions finite, ranges > 0) with `threads` OpenMP threads
  // (<= 0: all). Rebuilding reuses the storage of the last build.
  BuildTimes build(const std::vector<Light>& lights, int threads);
  // Moves light i to paths[i].at(turn) and builds, the move inside the build's first pass
  // over the lights; `path_bounds` (a box holding every path: LightPath::bounds) lets that
  // pass take the Morton codes too. A frame of moving lights makes two passes over memory
  // fewer than moving them and calling build().
  BuildTimes move_and_build(std::vector<Light>& lights, const std::vector<LightPath>& paths,
                            const LightPath::Turn& turn, const Aabb& path_bounds, int threads);

  // `out` = the lights that may reach point p (see above), in increasing index.
  void lights_near(const vec4& p, std::vector<std::uint32_t>& out) const;
  // `out` = the lights that may reach a point of `box` (a non-empty box), in increasing
  // index, found by walking the tree.
  void lights_near(const Aabb& box, std::vector<std::uint32_t>& out) const;
  // The same list found by testing every light (the papers' "brute force" assignment).
  void lights_near_brute_force(const Aabb& box, std::vector<std::uint32_t>& out) const;

  std::size_t light_count() const { return padded_.size(); }
  // Lights without a range: every query returns them.
  const std::vector<std::uint32_t>& unbounded() const { return unbounded_; }
  // Whether some light has a range (else every query returns every light).
  bool has_bounded() const { return !order_.empty(); }
  // Levels of the tree (0 when no light has a range) and its bytes.
  std::size_t levels() const { return levels_.size(); }
  std::size_t bytes() const;

 private:
  // Four boxes, structure of arrays: lo[axis][child], hi[axis][child]. An unused slot is
  // empty (lo = +inf, hi = -inf): no point or box is inside it.
  struct alignas(16) Block {
    float lo[3][4];
    float hi[3][4];
  };
  template <typename Position>
  BuildTimes build_with(const std::vector<Light>& lights, Position position, const Aabb* known,
                        int threads);
  template <typename Overlaps, typename Accept>
  void walk(Overlaps overlaps, Accept accept, std::vector<std::uint32_t>& out) const;
  void finish(std::vector<std::uint32_t>& out) const;

  std::vector<vec4> padded_;               // per light: position, w = padded range (inf: none)
  std::vector<std::uint32_t> unbounded_;   // lights without a range, increasing
  std::vector<std::uint32_t> order_;       // level-0 entry -> light index (Morton order)
  std::vector<vec4> sorted_;               // level-0 entry -> its padded sphere
  std::vector<std::vector<Block>> levels_;  // [0]: groups of 4 lights; back(): one block
  std::vector<std::uint32_t> codes_;       // build scratch (kept to avoid reallocation)
};

}  // namespace rt2
