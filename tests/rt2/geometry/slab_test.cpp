// The BVH's slab test at its edge cases: rays with zero direction components (infinite
// reciprocals), axis-parallel rays lying exactly in a box face or running along a box edge,
// and rays grazing a face, against a grid of boxes whose faces and edges line up with the
// BVH's own boxes. A box culled wrongly would lose a hit that brute force finds.
#include <gtest/gtest.h>

#include "rt2/scene/shapes.h"
#include "rt2/render/trace.h"
#include "tests/rt2/test_util.h"

namespace rt2 {
namespace {

// 4 x 4 x 4 boxes [i, i + 0.75]^3 (integer-aligned faces), split into 2 triangles per face.
Scene box_grid() {
  std::vector<Mesh> meshes;
  for (int x = 0; x < 4; ++x)
    for (int y = 0; y < 4; ++y)
      for (int z = 0; z < 4; ++z)
        meshes.push_back(make_box(vec4(float(x), float(y), float(z)),
                                  vec4(x + 0.75f, y + 0.75f, z + 0.75f), 1, 0));
  return test::geometry_scene(meshes);
}

// Coordinates that are exactly on box planes (0, 0.75, 1, 1.75, ...) or between them.
float plane_or_gap(std::mt19937& rng) {
  const int k = static_cast<int>(rng() % 8);
  const float base = float(k / 2);
  return (k % 2 ? base + 0.75f : base) + ((rng() % 3 == 0) ? 0.375f : 0.0f);
}

// The wide BVH's closest hit against brute force, for every runnable ISA (BVH width) and
// both triangle tests; returns the number of hits.
std::size_t compare_with_brute_force(const Scene& scene, const BvhConfig& config,
                                     const std::vector<Ray>& rays) {
  std::size_t hits = 0;
  for (Isa isa : test::runnable_isas()) {
    const Accel acc = Accel::build(scene, config, isa);
    for (bool watertight : {false, true}) {
      hits = 0;
      for (const Ray& r : rays) {
        const Hit bvh = trace_closest(acc, r, kInfinity, {watertight});
        const Hit ref = test::brute_force(acc, r, 0.0f, kInfinity, watertight);
        EXPECT_EQ(bvh.found(), ref.found())
            << str(r.org) << " " << str(r.dir) << " " << isa_name(isa) << " " << watertight;
        if (bvh.found() && ref.found()) {
          EXPECT_EQ(bvh.t, ref.t);
        }
        hits += ref.found();
      }
    }
  }
  return hits;
}

TEST(Slab, AxisParallelRaysInFacePlanesAndAlongEdgesAreNotCulled) {
  const Scene scene = box_grid();
  for (std::uint32_t leaf : {1u, 4u, 16u}) {
    std::mt19937 rng(leaf);
    std::vector<Ray> rays;
    for (int i = 0; i < 20000; ++i) {
      const int axis = static_cast<int>(rng() % 3);
      vec4 o(plane_or_gap(rng), plane_or_gap(rng), plane_or_gap(rng));
      o[axis] = (rng() % 2) ? -1.0f : 5.0f;  // outside the grid along the ray's axis
      vec4 d(0, 0, 0);
      d[axis] = o[axis] < 0 ? 1.0f : -1.0f;
      rays.emplace_back(o, d);
    }
    EXPECT_GT(compare_with_brute_force(scene, BvhConfig{leaf, Split::sah, 16}, rays), 1000u);
  }
}

TEST(Slab, RaysWithOneZeroComponentSweepingAcrossFacesAreNotCulled) {
  const Scene scene = box_grid();
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<Ray> rays;
  for (int i = 0; i < 20000; ++i) {
    const int flat = static_cast<int>(rng() % 3);
    vec4 o(plane_or_gap(rng), plane_or_gap(rng), plane_or_gap(rng));
    vec4 d(u(rng), u(rng), u(rng));
    d[flat] = 0.0f;  // lies in the plane o[flat] = const, possibly a face plane
    if (float(dot(d, d)) < 1e-6f) continue;
    o = o - 6.0f * normalize(d);
    rays.emplace_back(o, normalize(d));
  }
  EXPECT_GT(compare_with_brute_force(scene, BvhConfig{4, Split::midpoint, 16}, rays), 1000u);
}

TEST(Slab, GrazingRaysAreNotCulled) {
  const Scene scene = box_grid();
  std::mt19937 rng(11);
  std::vector<Ray> rays;
  for (int i = 0; i < 20000; ++i) {
    const int axis = static_cast<int>(rng() % 3), other = (axis + 1) % 3;
    vec4 o(plane_or_gap(rng), plane_or_gap(rng), plane_or_gap(rng));
    o[axis] = -1.0f;
    vec4 d(0, 0, 0);
    d[axis] = 1.0f;
    d[other] = std::ldexp(1.0f, -static_cast<int>(10 + rng() % 30)) * ((rng() % 2) ? 1 : -1);
    rays.emplace_back(o, normalize(d));
  }
  EXPECT_GT(compare_with_brute_force(scene, BvhConfig{2, Split::sah, 16}, rays), 1000u);
}

TEST(Slab, BoxTestIsConservativeForRaysOnItsBoundary) {
  const Aabb box{vec4(0, 0, 0), vec4(1, 1, 1)};
  // Along each edge and in each face plane, both directions: never a miss.
  for (int axis = 0; axis < 3; ++axis)
    for (float a : {0.0f, 1.0f})
      for (float b : {0.0f, 0.5f, 1.0f})
        for (float dir : {1.0f, -1.0f}) {
          vec4 o(0, 0, 0), d(0, 0, 0);
          o[axis] = dir > 0 ? -2.0f : 3.0f;
          o[(axis + 1) % 3] = a;
          o[(axis + 2) % 3] = b;
          d[axis] = dir;
          EXPECT_NE(slab_entry(box.lo, box.hi, RayPre(Ray(o, d)), 0.0f, kInfinity), kInfinity)
              << str(o) << str(d);
        }
}

}  // namespace
}  // namespace rt2
