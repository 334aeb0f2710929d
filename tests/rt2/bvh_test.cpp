// The BVH: structure invariants of the builder, and closest / any hit through the
// traverser against brute force over every primitive.
#include <gtest/gtest.h>

#include <algorithm>
#include <tuple>

#include "rt2/accel.h"
#include "rt2/builtin_scene.h"
#include "rt2/error.h"
#include "tests/rt2/test_util.h"

namespace rt2 {
namespace {

using test::kSampleScale;

constexpr unsigned kAll = kAllFeatures;

// Checks closest_hit == brute force on `rays`; returns the number of rays that hit.
std::size_t expect_closest_equals_brute_force(const Accel& acc, const std::vector<Ray>& rays) {
  std::size_t hits = 0, mismatches = 0;
#pragma omp parallel for reduction(+ : hits, mismatches) schedule(dynamic, 256)
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const Hit bvh = closest_hit<kAll>(acc, rays[i], 0.0f, kInfinity);
    const Hit ref = test::brute_force(acc, rays[i], 0.0f, kInfinity);
    hits += ref.found();
    // Same distance exactly: each primitive's t does not depend on the visiting order.
    mismatches += !(bvh.t == ref.t && bvh.found() == ref.found());
  }
  EXPECT_EQ(mismatches, 0u);
  return hits;
}

class BvhVsBruteForce : public ::testing::TestWithParam<std::tuple<std::uint32_t, Split>> {};

TEST_P(BvhVsBruteForce, ClosestHitEqualsBruteForceOnRandomSoup) {
  const auto [leaf, split] = GetParam();
  const Scene scene = test::geometry_scene({test::random_soup(300, 0.4f, 7 + leaf)},
                                           {Sphere{vec4(0.3f, 0.2f, 0.1f), 0.2f}});
  const Accel acc = Accel::build(scene, BvhConfig{leaf, split, 16});
  const auto rays = test::random_rays(acc, 100000 / kSampleScale, 11 + leaf);
  const std::size_t hits = expect_closest_equals_brute_force(acc, rays);
  EXPECT_GT(hits, rays.size() / 3);  // the rays do exercise hits
}

std::string leaf_and_split_name(
    const ::testing::TestParamInfo<std::tuple<std::uint32_t, Split>>& p) {
  return "leaf" + std::to_string(std::get<0>(p.param)) +
         (std::get<1>(p.param) == Split::sah ? "_sah" : "_midpoint");
}

INSTANTIATE_TEST_SUITE_P(LeafSizesAndSplits, BvhVsBruteForce,
                         ::testing::Combine(::testing::Values(1u, 4u, 64u, 4096u),
                                            ::testing::Values(Split::midpoint, Split::sah)),
                         leaf_and_split_name);

TEST(Bvh, ClosestHitEqualsBruteForceOnTheChairMesh) {
  Scene scene = make_default_scene();
  scene.planes.clear();
  scene.plane_materials.clear();
  for (Split split : {Split::sah, Split::midpoint}) {
    const Accel acc = Accel::build(scene, BvhConfig{4, split, 16});
    const auto rays = test::random_rays(acc, 100000 / (2 * kSampleScale), 5, 1.5f);
    EXPECT_GT(expect_closest_equals_brute_force(acc, rays), rays.size() / 3);
  }
}

TEST(Bvh, AnyHitAgreesWithClosestHitOnSegments) {
  const Scene scene = test::geometry_scene({test::random_soup(500, 0.3f, 3)},
                                           {Sphere{vec4(0, 0, 0), 0.3f}});
  const Accel acc = Accel::build(scene, BvhConfig{4, Split::sah, 16});
  const auto rays = test::random_rays(acc, 50000 / kSampleScale, 4);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> len(0.0f, 4.0f);
  const std::vector<Material> opaque(1);
  std::size_t blocked = 0;
  for (const Ray& r : rays) {
    const float t_max = len(rng);
    const bool occluded = transmittance<kAll & ~kRefraction>(acc, opaque, r, 0.0f, t_max) == 0.0f;
    const bool hit = closest_hit<kAll>(acc, r, 0.0f, t_max).found();
    ASSERT_EQ(occluded, hit);
    blocked += occluded;
  }
  EXPECT_GT(blocked, rays.size() / 10);
}

TEST(Bvh, EveryPrimitiveIsInExactlyOneLeafAndLeavesRespectTheSizeLimit) {
  std::vector<Aabb> boxes;
  std::mt19937 rng(1);
  for (int i = 0; i < 1000; ++i) {
    Aabb b;
    const vec4 p = test::random_point(rng, -10, 10);
    b.grow(p);
    b.grow(p + test::random_point(rng, 0, 1));
    boxes.push_back(b);
  }
  for (std::uint32_t leaf : {1u, 3u, 64u, 5000u}) {
    const Bvh bvh = build_bvh(boxes, BvhConfig{leaf, Split::sah, 16});
    std::vector<int> seen(boxes.size(), 0);
    std::uint32_t leaves = 0;
    for (const BvhNode& n : bvh.nodes) {
      if (!n.is_leaf()) continue;
      ++leaves;
      EXPECT_LE(n.count, leaf);
      for (std::uint32_t i = n.offset; i < n.offset + n.count; ++i) ++seen[bvh.order[i]];
    }
    EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int c) { return c == 1; }));
    EXPECT_EQ(bvh.stats.leaves, leaves);
    EXPECT_EQ(bvh.stats.nodes, 2 * leaves - 1);  // a full binary tree
  }
}

TEST(Bvh, ChildBoxesAreInsideTheirParent) {
  const Scene scene = test::geometry_scene({test::random_soup(2000, 0.2f, 9)});
  const Accel acc = Accel::build(scene, BvhConfig{2, Split::midpoint, 16});
  const auto& nodes = acc.bvh.nodes;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (nodes[i].is_leaf()) continue;
    for (std::uint32_t c : {std::uint32_t(i + 1), nodes[i].offset})
      for (int a = 0; a < 3; ++a) {
        EXPECT_GE(nodes[c].lo[a], nodes[i].lo[a]);
        EXPECT_LE(nodes[c].hi[a], nodes[i].hi[a]);
      }
  }
}

TEST(Bvh, CoincidentPrimitivesStillSplitDownToLeafSizeOne) {
  Aabb b;
  b.grow(vec4(0, 0, 0));
  b.grow(vec4(1, 1, 1));
  const std::vector<Aabb> boxes(5000, b);
  const Bvh bvh = build_bvh(boxes, BvhConfig{1, Split::sah, 16});
  EXPECT_EQ(bvh.stats.leaves, 5000u);
  EXPECT_EQ(bvh.stats.max_leaf_prims, 1u);
  EXPECT_LT(bvh.stats.max_depth, kMaxBvhDepth);
}

TEST(Bvh, DepthStaysBoundedOnPathologicalClustering) {
  // Centroids at 2^-k: every midpoint split peels off one primitive.
  std::vector<Aabb> boxes;
  for (int k = 0; k < 3000; ++k) {
    Aabb b;
    const float x = std::ldexp(1.0f, -(k % 120));
    b.grow(vec4(x, 0, 0));
    b.grow(vec4(x, 1e-3f, 1e-3f));
    boxes.push_back(b);
  }
  const Bvh bvh = build_bvh(boxes, BvhConfig{1, Split::midpoint, 16});
  EXPECT_LT(bvh.stats.max_depth, kMaxBvhDepth);
  EXPECT_EQ(bvh.stats.leaves, 3000u);
}

TEST(Bvh, LeafLargerThanTheSceneIsOneLeafAndStillCorrect) {
  const Scene scene = test::geometry_scene({test::random_soup(200, 0.3f, 21)});
  const Accel acc = Accel::build(scene, BvhConfig{16384, Split::sah, 16});
  EXPECT_EQ(acc.bvh.stats.nodes, 1u);
  const auto rays = test::random_rays(acc, 5000, 22);
  expect_closest_equals_brute_force(acc, rays);
}

TEST(Bvh, EmptySceneHasNoNodesAndRaysMiss) {
  const Scene scene = test::geometry_scene({});
  const Accel acc = Accel::build(scene, BvhConfig{});
  EXPECT_TRUE(acc.bvh.nodes.empty());
  EXPECT_FALSE((closest_hit<kAll>(acc, Ray(vec4(0, 0, 0), vec4(0, 0, -1)), 0, kInfinity).found()));
}

TEST(Bvh, BuilderRejectsAbsurdConfiguration) {
  EXPECT_THROW(build_bvh({}, BvhConfig{0, Split::sah, 16}), Error);
  EXPECT_THROW(build_bvh({}, BvhConfig{4, Split::sah, 1}), Error);
  static_assert(sizeof(BvhNode) == 32);
}

TEST(Bvh, LeafOrderKeepsEachLeafsTrianglesContiguous) {
  const Scene scene = test::geometry_scene({test::random_soup(1000, 0.2f, 31)});
  const Accel acc = Accel::build(scene, BvhConfig{8, Split::sah, 16});
  for (std::size_t i = 0; i < acc.refs.size(); ++i) {
    EXPECT_EQ(prim_tag(acc.refs[i]), kTriangleTag);
    EXPECT_EQ(prim_index(acc.refs[i]), i);  // triangles stored in leaf order
  }
}

}  // namespace
}  // namespace rt2
