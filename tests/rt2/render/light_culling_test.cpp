// Lights with a range and the culling modes that skip the others (rt2::LightCulling):
// every mode gives the image of brute force over all lights, bit for bit, on random scenes of
// 1 ... 10^4 lights; the window reaches 0 at the range; shadows can be turned off.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "rt2/lights/cluster_visibility.h"
#include "rt2/render/compiled_scene.h"
#include "rt2/render/trace.h"
#include "rt2/scene/light.h"
#include "rt2/scene/light_path.h"
#include "rt2/render/schedule.h"
#include "tests/rt2/test_util.h"

namespace rt2 {
namespace {

bool identical(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height &&
         std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)) == 0;
}

// The glass scene (mirrors, glass, a checker floor: primary, shadow, reflected and refracted
// rays) with n lights around it. Their ranges shrink as n grows, so a point sees a few to a
// few dozen lights; one light in 97 has no range.
Scene many_light_scene(std::size_t n, unsigned seed) {
  Scene s = test::glass_scene();
  s.lights.clear();
  std::mt19937 rng(seed);
  const float hi = 2.5f / std::cbrt(float(n));
  std::uniform_real_distribution<float> range(0.3f * hi, hi), x(-1.5f, 2.0f), y(0.02f, 1.5f),
      z(-1.2f, 1.2f), c(0.2f, 1.0f);
  for (std::size_t i = 0; i < n; ++i) {
    Light l;
    l.position = vec4(x(rng), y(rng), z(rng));
    l.color = vec4(c(rng), c(rng), c(rng));
    l.intensity = 0.6f;
    l.range = i % 97 == 5 ? kInfinity : range(rng);
    s.lights.push_back(l);
  }
  return s;
}

RenderSettings small(LightCulling culling, LightLists lists = LightLists::bvh) {
  RenderSettings st;
  st.width = 40;
  st.height = 30;
  st.depth = 3;
  st.light_culling = culling;
  st.light_lists = lists;
  return st;
}

struct Mode {
  LightCulling culling;
  LightLists lists;
  const char* name;
};
const Mode kModes[] = {{LightCulling::tiled, LightLists::bvh, "tiled/bvh"},
                       {LightCulling::tiled, LightLists::brute_force, "tiled/brute-force"},
                       {LightCulling::clustered, LightLists::bvh, "clustered/bvh"},
                       {LightCulling::clustered, LightLists::brute_force, "clustered/brute-force"},
                       {LightCulling::bvh, LightLists::bvh, "bvh"}};

TEST(LightCulling, EveryModeGivesTheBruteForceImageBitForBit) {
  for (std::size_t n : {1u, 3u, 10u, 100u, 1000u, 10000u}) {
    const Scene s = many_light_scene(n, unsigned(n));
    FrameResult brute_result;
    const Image brute = test::render_scene(s, small(LightCulling::none), {Backend::serial, 1, 1},
                                           {}, best_isa(), &brute_result);
    ASSERT_GT(brute_result.rays.lights.in_range, 0u) << n;
    for (const Mode& m : kModes) {
      FrameResult r;
      const Image img = test::render_scene(s, small(m.culling, m.lists), {Backend::omp, 2, 2},
                                           {}, best_isa(), &r);
      ASSERT_TRUE(identical(brute, img)) << n << " lights, " << m.name;
      // The same lights in range at the same points: culling only skipped the others.
      EXPECT_EQ(r.rays.lights.in_range, brute_result.rays.lights.in_range) << n << m.name;
      // Every shadow ray of brute force is traced, or proven unoccluded by a cluster.
      EXPECT_EQ(r.rays.shadow + r.rays.lights.unoccluded, brute_result.rays.shadow)
          << n << m.name;
    }
  }
}

// Long light lists are shaded kLightLanes lights at a time (light_terms.h's
// add_light_terms_lanes): the same image, shadow rays and counts as one light at a time, on
// every instruction set, without culling (every light at every point) and with lists.
// Phong and physically based materials alike (the PBR scene: every material turned pbr,
// from a smooth metal to a rough dielectric).
TEST(LightLanes, LightsInLanesGiveTheOneByOneImageAndRaysOnEveryIsa) {
  for (std::size_t n : {12u, 300u, 3000u})
    for (bool pbr : {false, true}) {
    Scene s = many_light_scene(n, unsigned(n) + 7);
    if (pbr)
      for (std::size_t i = 0; i < s.materials.size(); ++i) {
        Material& mat = s.materials[i];
        mat.model = Shading::pbr;
        mat.base_color = vec4(0.9f, 0.6f, 0.4f);
        mat.metallic = float(i % 3) * 0.5f;
        mat.roughness = float(i % 4) / 3.0f;
      }
    for (const Mode& m : {Mode{LightCulling::none, LightLists::bvh, "none"},
                          Mode{LightCulling::clustered, LightLists::bvh, "clustered/bvh"},
                          Mode{LightCulling::bvh, LightLists::bvh, "bvh"}})
      for (Isa isa : test::runnable_isas()) {
        RenderSettings st = small(m.culling, m.lists);
        st.shading_lanes = false;
        FrameResult one, lanes;
        const Image ref = test::render_scene(s, st, {Backend::serial, 1, 1}, {}, isa, &one);
        st.shading_lanes = true;
        const Image img = test::render_scene(s, st, {Backend::serial, 1, 1}, {}, isa, &lanes);
        const std::string what = std::to_string(n) + " lights, " + m.name + ", " + isa_name(isa) +
                                 (pbr ? ", pbr" : ", phong");
        EXPECT_TRUE(identical(ref, img)) << what;
        EXPECT_EQ(one.rays.shadow, lanes.rays.shadow) << what;
        EXPECT_EQ(one.rays.lights.in_range, lanes.rays.lights.in_range) << what;
        EXPECT_EQ(one.rays.lights.unoccluded, lanes.rays.lights.unoccluded) << what;
        EXPECT_EQ(one.rays.lights.light_lanes, 0u) << what;
        // most lights are considered in lanes (12 lights culled make lists too short)
        if (n > 12 || m.culling == LightCulling::none) {
          EXPECT_GT(lanes.rays.lights.light_lanes, lanes.rays.lights.considered / 2) << what;
        }
      }
    }
}

// Blocks (the tiles of tiled culling), depth slices, samples and passes change the lists,
// never the image.
TEST(LightCulling, BlocksSlicesAndPassesGiveTheSameImage) {
  const Scene s = many_light_scene(500, 3);
  RenderSettings st = small(LightCulling::none);
  st.subpixels = 4;
  const Image brute = test::render_scene(s, st);
  for (LightCulling c : {LightCulling::tiled, LightCulling::clustered})
    for (int block : {1, 5, 16, 64})
      for (int slices : {1, 3, 16, 256})
        for (int passes : {1, 4}) {
          st.light_culling = c;
          st.block = block;
          st.light_slices = slices;
          st.passes = passes;
          ASSERT_TRUE(identical(brute, test::render_scene(s, st)))
              << int(c) << " block " << block << " slices " << slices << " passes " << passes;
        }
}

// Culling must cull: with many small lights, a point considers a small part of them.
TEST(LightCulling, ListsHoldFarFewerLightsThanTheScene) {
  const Scene s = many_light_scene(10000, 5);
  for (const Mode& m : kModes) {
    FrameResult r;
    test::render_scene(s, small(m.culling, m.lists), {Backend::serial, 1, 1}, {}, best_isa(), &r);
    const LightCounts& l = r.rays.lights;
    ASSERT_GT(l.points, 0u);
    // A tile's list serves points at every depth of its block: the loosest of the modes.
    const double most = m.culling == LightCulling::tiled ? 10000 / 5.0 : 10000 / 50.0;
    EXPECT_LT(double(l.considered) / double(l.points), most) << m.name;
    EXPECT_GE(l.considered, l.in_range) << m.name;
  }
}

TEST(LightRange, WindowIsOneAtTheLightZeroAtTheRangeAndDecreasing) {
  Light l;
  l.range = 2.0f;
  EXPECT_EQ(range_window(l, 0.0f), 1.0f);
  EXPECT_FALSE(in_range(l, 2.0f));
  EXPECT_TRUE(in_range(l, std::nextafter(2.0f, 0.0f)));
  EXPECT_LT(range_window(l, std::nextafter(2.0f, 0.0f)), 1e-12f);
  float last = 1.0f;
  for (float d = 0.01f; d < 2.0f; d += 0.01f) {
    const float w = range_window(l, d);
    ASSERT_LE(w, last) << d;
    ASSERT_GE(w, 0.0f) << d;
    last = w;
  }
  // Smooth at the range: the slope there is 0 (w(d) ~ 32 (1 - d/r)^2 near it).
  const float e = 1e-3f;
  EXPECT_LT(range_window(l, 2.0f - e) / e, 0.01f);
}

// A light without a range is the thesis's light; a huge range is the same to the last bit
// (its window is exactly 1 in float), and a range that reaches nothing leaves only ambient.
TEST(LightRange, HugeRangeIsNoRangeAndAShortRangeLightsNothing) {
  Scene s = test::glass_scene();
  const RenderSettings st = small(LightCulling::bvh);
  const Image none = test::render_scene(s, st);
  for (Light& l : s.lights) l.range = 1e30f;
  EXPECT_TRUE(identical(none, test::render_scene(s, st)));
  for (Light& l : s.lights) l.range = 1e-3f;  // the lights are far above the scene
  const Image dark = test::render_scene(s, st);
  s.lights.clear();
  EXPECT_TRUE(identical(dark, test::render_scene(s, st)));
}

// In range, the term is scaled by the window: a lit point's colour rises as the range grows.
TEST(LightRange, ALongerRangeLightsMore) {
  Scene s = test::glass_scene();
  s.lights.resize(1);
  double last = -1.0;
  for (float range : {5.5f, 6.5f, 9.0f, 30.0f}) {  // the scene is ~5.1 from the light
    s.lights[0].range = range;
    const Image img = test::render_scene(s, small(LightCulling::none));
    double sum = 0.0;
    for (float v : img.rgb) sum += v;
    EXPECT_GT(sum, last) << range;
    last = sum;
  }
}

// Without shadow rays, every light that a point faces reaches it: no pixel is darker, some
// (in the shadows) are brighter, and no shadow ray is traced.
TEST(Shadows, OffTracesNoShadowRaysAndDarkensNothing) {
  const Scene s = test::glass_scene();
  RenderSettings st = small(LightCulling::bvh);
  FrameResult on_result, off_result;
  const Image on = test::render_scene(s, st, {Backend::serial, 1, 1}, {}, best_isa(), &on_result);
  st.shadows = false;
  const Image off = test::render_scene(s, st, {Backend::serial, 1, 1}, {}, best_isa(), &off_result);
  EXPECT_EQ(off_result.rays.shadow_walk.nodes, 0u);
  EXPECT_GT(on_result.rays.shadow_walk.nodes, 0u);
  std::size_t brighter = 0;
  for (std::size_t i = 0; i < on.rgb.size(); ++i) {
    ASSERT_GE(off.rgb[i], on.rgb[i] * (1.0f - 1e-6f)) << i;
    brighter += off.rgb[i] > on.rgb[i] * 1.01f + 1e-4f;
  }
  EXPECT_GT(brighter, 0u);
}

// Moving lights (CompiledScene::move_lights) render as the same lights placed there from the
// start, in every mode.
TEST(LightMotion, MovedLightsRenderAsLightsCompiledThere) {
  const Scene s = many_light_scene(300, 7);
  CompiledScene moving = CompiledScene::compile(s, {});
  moving.move_lights(1.7, 2);
  Scene placed = s;
  placed.lights = moving.lights;
  for (const Mode& m : kModes) {
    const RenderSettings st = small(m.culling, m.lists);
    Image a;
    render_frame(Renderer(moving, View{s.camera, st}), {Backend::omp, 2, 1}, a);
    ASSERT_TRUE(identical(a, test::render_scene(placed, st))) << m.name;
  }
}

TEST(LightMotion, PathsStartAtTheLightAndStayOnTheirCircle) {
  Light l;
  l.range = 2.0f;
  l.position = vec4(1.0f, 2.0f, 3.0f);
  for (std::size_t i : {0u, 1u, 1000u}) {
    const LightPath path(l, i, 10.0f);
    const vec4 p0 = path.at(LightPath::turn(0.0));
    EXPECT_EQ(float(dot(p0 - l.position, p0 - l.position)), 0.0f);
    const vec4 p2 = path.at(LightPath::turn(2.0));  // half a turn: a diameter away
    EXPECT_NEAR(std::sqrt(float(dot(p2 - l.position, p2 - l.position))), 2.0f, 1e-5f);
    EXPECT_EQ(p2[1], l.position[1]);
    for (double t : {0.3, 1.1, 2.9, 100.0}) {  // on the circle of radius 1 round its centre
      const vec4 centre = 0.5f * (p0 + p2);
      const vec4 p = path.at(LightPath::turn(t));
      EXPECT_NEAR(std::sqrt(float(dot(p - centre, p - centre))), 1.0f, 1e-5f) << t;
    }
  }
}

// Stage times are measured only when asked for (they cost a clock read per stage).
TEST(StageTimes, ZeroByDefaultAndEveryStageTimedWhenAsked) {
  const Scene s = many_light_scene(100, 9);
  RenderSettings st = small(LightCulling::clustered);
  FrameResult off, on;
  test::render_scene(s, st, {Backend::serial, 1, 1}, {}, best_isa(), &off);
  EXPECT_EQ(off.rays.stages.total(), 0u);
  st.stage_times = true;
  test::render_scene(s, st, {Backend::serial, 1, 1}, {}, best_isa(), &on);
  const StageTimes& t = on.rays.stages;
  EXPECT_GT(t.generate, 0u);
  EXPECT_GT(t.intersect, 0u);
  EXPECT_GT(t.lights, 0u);
  EXPECT_GT(t.shade, 0u);
  EXPECT_GT(t.shadow, 0u);
  EXPECT_GT(t.film, 0u);
}

// Lists of tiles and clusters skip the shadow rays of lights their hits provably see: the
// rays not traced are counted, and on these scenes there are some.
TEST(ClusterVisibility, ClustersProveSomeShadowRaysAndEveryModeStillMatches) {
  const Scene s = many_light_scene(2000, 13);
  FrameResult r;
  test::render_scene(s, small(LightCulling::clustered), {Backend::serial, 1, 1}, {}, best_isa(),
                     &r);
  EXPECT_GT(r.rays.lights.unoccluded, 0u);
  EXPECT_GT(r.rays.shadow, 0u);
}

// The proof against the oracle at scales where the ray tests round most: a ground sphere
// of radius 1e5 whose top is at y = 0 (its near root loses ~r 2^-24 to c = |o-c|^2 - r^2)
// with lights just above it, and a thin triangle reaching 1e7 units away (its edges round
// to ulp(1e7) = 1) beside a small cluster; what sees() claims, brute-force rays confirm.
TEST(ClusterVisibility, HugePrimitivesRoundingDoesNotBreakTheProof) {
  Scene s = test::glass_scene();
  s.spheres.push_back(Sphere{vec4(0.0f, -1e5f, 0.0f), 1e5f});
  s.sphere_materials.push_back(0);
  Mesh m;
  m.name = "needle";
  m.positions = {vec4(-1e7f, 0.0f, 0.0f), vec4(0.7f, 0.0f, 1.0f), vec4(0.7f, 0.0f, -1.0f)};
  m.faces.push_back({0, 1, 2});
  m.face_materials.push_back(0);
  s.meshes.push_back(m);
  const CompiledScene c = CompiledScene::compile(s, {});
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  ClusterVisibility v;
  for (int k = 0; k < 600 / test::kSampleScale; ++k) {
    Aabb cluster;
    const vec4 corner(4.0f * u(rng) - 2.0f, 0.01f + 0.5f * u(rng), 4.0f * u(rng) - 2.0f);
    cluster.grow(corner);
    if (k % 2) cluster.grow(corner + vec4(0.2f * u(rng), 0.2f * u(rng), 0.2f * u(rng)));
    const vec4 light(4.0f * u(rng) - 2.0f, (k % 3 == 0 ? -0.5f : 0.001f) + 0.01f * u(rng),
                     4.0f * u(rng) - 2.0f);
    Aabb reach = cluster;
    reach.grow(light);
    v.gather(c.accel, cluster, reach);
    if (!v.sees(light)) continue;
    for (int p = 0; p < 16; ++p) {
      const vec4 from = cluster.lo + vec4(u(rng), u(rng), u(rng)) * cluster.extent();
      const vec4 to = light - from;
      const float dist = std::sqrt(float(dot(to, to)));
      const Ray ray(from, to / dist);
      for (bool watertight : {false, true})
        ASSERT_FALSE(test::brute_force(c.accel, ray, 0.0f, dist, watertight).found())
            << "cluster " << k << " ray " << p;
    }
  }
}

// The proof against the oracle: whenever sees() says so, rays from points of the cluster
// to the light meet nothing (brute force over every triangle, sphere and plane), including
// rays from the cluster's corners.
TEST(ClusterVisibility, WhatItProvesEveryRayConfirms) {
  for (unsigned seed : {1u, 2u, 3u}) {
    Scene s = test::glass_scene();
    s.meshes.push_back(test::random_soup(300, 0.3f, seed));
    s.sphere_materials.push_back(0);
    s.spheres.push_back(Sphere{vec4(0.2f, 0.6f, 0.1f), 0.1f});
    const CompiledScene c = CompiledScene::compile(s, {});
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f), size(0.0f, 0.6f);
    ClusterVisibility v;
    std::size_t proven = 0, tested = 0;
    for (int k = 0; k < 150 / test::kSampleScale; ++k) {
      Aabb cluster;
      const vec4 corner = test::random_point(rng, -1.5f, 1.5f) + vec4(0.0f, 1.0f, 0.0f);
      cluster.grow(corner);
      cluster.grow(corner + vec4(size(rng), size(rng), size(rng)));
      std::vector<vec4> lights;
      Aabb reach = cluster;
      for (int l = 0; l < 8; ++l) {
        lights.push_back(cluster.center() + test::random_point(rng, -1.5f, 1.5f));
        reach.grow(lights.back());
      }
      v.gather(c.accel, cluster, reach);
      for (const vec4& light : lights) {
        ++tested;
        if (!v.sees(light)) continue;
        ++proven;
        for (int p = 0; p < 16; ++p) {
          vec4 from = cluster.lo + vec4(u(rng), u(rng), u(rng)) * cluster.extent();
          if (p < 8)
            from = vec4((p & 1) ? cluster.hi[0] : cluster.lo[0], (p & 2) ? cluster.hi[1] : cluster.lo[1],
                        (p & 4) ? cluster.hi[2] : cluster.lo[2]);
          const vec4 to = light - from;
          const float dist = std::sqrt(float(dot(to, to)));
          if (!(dist > 0.0f)) continue;
          const Ray ray(from, to / dist);
          for (bool watertight : {false, true})
            ASSERT_FALSE(test::brute_force(c.accel, ray, 0.0f, dist, watertight).found())
                << "seed " << seed << " cluster " << k << " ray " << p;
          float passed = 0.0f;
          trace_transmittance(c.accel, c.materials, TraceOptions{}, &ray, &dist, 1, &passed);
          ASSERT_EQ(passed, 1.0f);
        }
      }
    }
    EXPECT_GT(proven, tested / 20) << seed;  // it proves something
    EXPECT_LT(proven, tested) << seed;       // and not everything
  }
}

}  // namespace
}  // namespace rt2
