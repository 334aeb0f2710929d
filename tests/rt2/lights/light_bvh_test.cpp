// The light tree (rt2/lights/light_bvh.h) against brute force: a point query returns every light in
// range (rt2/scene/light.h's in_range, the test shading applies) in scene order, a box query
// returns exactly the brute-force assignment, at every size, after moving, and at the extremes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "rt2/render/compiled_scene.h"
#include "rt2/lights/light_bvh.h"
#include "tests/rt2/test_util.h"

namespace rt2 {
namespace {

// n lights in [-spread, spread]^3 with ranges in [lo, hi]; every `unbounded_every`-th light
// (when > 0) has no range.
std::vector<Light> random_lights(std::size_t n, float spread, float lo, float hi, unsigned seed,
                                 std::size_t unbounded_every = 0) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> r(lo, hi);
  std::vector<Light> lights(n);
  for (std::size_t i = 0; i < n; ++i) {
    lights[i].position = test::random_point(rng, -spread, spread);
    lights[i].range = r(rng);
    if (unbounded_every > 0 && i % unbounded_every == 0) lights[i].range = kInfinity;
  }
  return lights;
}

// The lights in range of p as shading decides it, in scene order.
std::vector<std::uint32_t> in_range_of(const std::vector<Light>& lights, const vec4& p) {
  std::vector<std::uint32_t> out;
  for (std::uint32_t i = 0; i < lights.size(); ++i) {
    const vec4 to = lights[i].position - p;
    if (in_range(lights[i], std::sqrt(float(dot(to, to))))) out.push_back(i);
  }
  return out;
}

// `found` is increasing and contains every light of `needed`.
void expect_superset_in_order(const std::vector<std::uint32_t>& found,
                              const std::vector<std::uint32_t>& needed, const char* what) {
  ASSERT_TRUE(std::is_sorted(found.begin(), found.end())) << what;
  ASSERT_TRUE(std::adjacent_find(found.begin(), found.end()) == found.end()) << what;
  ASSERT_TRUE(std::includes(found.begin(), found.end(), needed.begin(), needed.end())) << what;
}

TEST(LightBvh, PointQueryHoldsEveryLightInRangeInSceneOrder) {
  for (std::size_t n : {1u, 2u, 3u, 4u, 5u, 17u, 64u, 1000u, 10000u}) {
    const std::vector<Light> lights = random_lights(n, 5.0f, 0.2f, 2.0f, unsigned(n), 7);
    LightBvh bvh;
    bvh.build(lights, 2);
    std::mt19937 rng(3);
    std::vector<std::uint32_t> found;
    std::size_t total = 0;
    for (int k = 0; k < 2000 / test::kSampleScale; ++k) {
      // Points anywhere, and points right at a light's range (the sphere's surface).
      vec4 p = test::random_point(rng, -6.0f, 6.0f);
      if (k % 2) {
        const Light& l = lights[rng() % n];
        if (l.has_range()) p = l.position + test::random_direction(rng) * l.range;
      }
      bvh.lights_near(p, found);
      const std::vector<std::uint32_t> needed = in_range_of(lights, p);
      expect_superset_in_order(found, needed, "point query");
      total += needed.size();
    }
    EXPECT_GT(total, 0u) << n;
  }
}

// The tree only skips lights: what it returns beyond the lights in range are lights whose
// padded sphere holds the point, so a point query is not the whole list.
TEST(LightBvh, PointQueryReturnsOnlyLightsWhosePaddedSphereHoldsThePoint) {
  const std::vector<Light> lights = random_lights(5000, 5.0f, 0.2f, 0.6f, 11);
  LightBvh bvh;
  bvh.build(lights, 1);
  std::mt19937 rng(5);
  std::vector<std::uint32_t> found;
  for (int k = 0; k < 1000; ++k) {
    const vec4 p = test::random_point(rng, -5.0f, 5.0f);
    bvh.lights_near(p, found);
    for (std::uint32_t i : found) {
      const vec4 to = lights[i].position - p;
      ASSERT_LE(std::sqrt(float(dot(to, to))), lights[i].range * (1.0f + 1e-4f));
    }
  }
}

TEST(LightBvh, BoxQueryEqualsBruteForceAssignment) {
  for (std::size_t n : {1u, 4u, 5u, 100u, 3000u}) {
    const std::vector<Light> lights = random_lights(n, 5.0f, 0.1f, 1.5f, unsigned(n) + 1, 13);
    LightBvh bvh;
    bvh.build(lights, 2);
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> size(0.0f, 2.0f);
    std::vector<std::uint32_t> tree, brute;
    for (int k = 0; k < 500; ++k) {
      Aabb box;
      const vec4 c = test::random_point(rng, -6.0f, 6.0f);
      box.grow(c);
      if (k % 5) box.grow(c + vec4(size(rng), size(rng), size(rng)));  // else a point box
      bvh.lights_near(box, tree);
      bvh.lights_near_brute_force(box, brute);
      ASSERT_EQ(tree, brute) << n << " lights, box " << k;
      // Every point of the box: its lights in range are in the box's list.
      std::uniform_real_distribution<float> u(0.0f, 1.0f);
      const vec4 p = box.lo + vec4(u(rng), u(rng), u(rng)) * box.extent();
      expect_superset_in_order(tree, in_range_of(lights, p), "box query");
    }
  }
}

TEST(LightBvh, LightsWithoutRangeAreInEveryAnswer) {
  std::vector<Light> lights = random_lights(200, 5.0f, 0.1f, 0.2f, 17, 50);  // 0, 50, 100, 150
  LightBvh bvh;
  bvh.build(lights, 1);
  EXPECT_EQ(bvh.unbounded(), (std::vector<std::uint32_t>{0, 50, 100, 150}));
  std::vector<std::uint32_t> found;
  bvh.lights_near(vec4(1e6f, 1e6f, 1e6f), found);  // far from every bounded light
  EXPECT_EQ(found, bvh.unbounded());
  Aabb far;
  far.grow(vec4(1e6f, 0.0f, 0.0f));
  bvh.lights_near(far, found);
  EXPECT_EQ(found, bvh.unbounded());
  // No light with a range: no tree, and every query is every light.
  for (Light& l : lights) l.range = kInfinity;
  bvh.build(lights, 1);
  EXPECT_FALSE(bvh.has_bounded());
  EXPECT_EQ(bvh.levels(), 0u);
  bvh.lights_near(vec4(0.0f, 0.0f, 0.0f), found);
  EXPECT_EQ(found.size(), lights.size());
}

TEST(LightBvh, RebuildingAfterMovingAnswersAsAFreshBuild) {
  Scene s = test::glass_scene();
  s.lights = random_lights(3000, 3.0f, 0.1f, 0.5f, 19);
  CompiledScene c = CompiledScene::compile(s, {});
  std::mt19937 rng(21);
  std::vector<std::uint32_t> moved, fresh;
  for (double t : {0.5, 1.25, 3.0}) {
    const LightBvh::BuildTimes times = c.move_lights(t, 2);
    EXPECT_GE(times.total_ms(), times.sort_ms);
    LightBvh reference;
    reference.build(c.lights, 1);
    for (int k = 0; k < 500; ++k) {
      const vec4 p = test::random_point(rng, -3.0f, 3.0f);
      c.light_bvh.lights_near(p, moved);
      reference.lights_near(p, fresh);
      ASSERT_EQ(moved, fresh) << t;
      expect_superset_in_order(moved, in_range_of(c.lights, p), "moved");
    }
  }
  // Time 0 is where the lights were compiled.
  c.move_lights(0.0, 1);
  for (std::size_t i = 0; i < s.lights.size(); ++i)
    ASSERT_EQ(float(dot(c.lights[i].position - s.lights[i].position,
                        c.lights[i].position - s.lights[i].position)),
              0.0f);
}

// Tiny ranges far from the origin, where an ulp of the coordinates is a large part of the
// range; huge ranges; lights all at one point; lights along one axis (flat Morton bounds).
TEST(LightBvh, ExtremesFarOriginsTinyAndHugeRangesCoincidentAndFlatLights) {
  std::mt19937 rng(23);
  const auto check = [&](const std::vector<Light>& lights, float spread, const vec4& centre,
                         const char* what) {
    LightBvh bvh;
    bvh.build(lights, 2);
    std::vector<std::uint32_t> found;
    for (int k = 0; k < 1000; ++k) {
      vec4 p = centre + test::random_point(rng, -spread, spread);
      if (k % 2) {
        const Light& l = lights[rng() % lights.size()];
        p = l.position + test::random_direction(rng) * (l.range * 0.999f);
      }
      bvh.lights_near(p, found);
      expect_superset_in_order(found, in_range_of(lights, p), what);
    }
  };
  // Far from the origin: ranges of a few ulps of the coordinates (ulp(2e5) = 1/64).
  const vec4 far(1e5f, -2e5f, 5e4f);
  std::vector<Light> lights = random_lights(500, 1.0f, 0.03f, 0.1f, 29);
  for (Light& l : lights) l.position += far;
  check(lights, 1.0f, far, "far origin, small ranges");
  lights = random_lights(300, 10.0f, 1e10f, 1e30f, 31);
  check(lights, 1e12f, vec4(0.0f, 0.0f, 0.0f), "huge ranges");
  lights = random_lights(50, 1.0f, 1.0f, 2.0f, 43);  // ranges whose padding overflows
  lights[3].range = lights[7].range = std::numeric_limits<float>::max();
  check(lights, 3.0f, vec4(0.0f, 0.0f, 0.0f), "largest finite range");
  lights = random_lights(100, 0.0f, 0.5f, 1.0f, 37);
  check(lights, 1.0f, vec4(0.0f, 0.0f, 0.0f), "coincident");
  lights = random_lights(400, 5.0f, 0.1f, 0.3f, 41);
  for (Light& l : lights) l.position = vec4(l.position[0], 0.0f, 0.0f);
  check(lights, 0.3f, vec4(0.0f, 0.0f, 0.0f), "flat");
}

}  // namespace
}  // namespace rt2
