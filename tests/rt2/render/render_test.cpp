// Whole frames: every instruction set (and so both BVH widths), backend, thread count and
// grain give bit-identical images; features are detected; ray counts follow the settings; bad
// settings are rejected.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "mlib/fpmode.h"
#include "rt2/scene/builtin_scene.h"
#include "rt2/base/error.h"
#include "rt2/render/schedule.h"
#include "tests/rt2/test_util.h"

namespace rt2 {
namespace {

Image render(const Scene& scene, const RenderSettings& st, const Schedule& sched,
             RayCounts* rays = nullptr, BvhConfig bvh = {}, Isa isa = best_isa()) {
  FrameResult fr;
  const Image img = test::render_scene(scene, st, sched, bvh, isa, &fr);
  if (rays) *rays = fr.rays;
  return img;
}

RenderSettings small(int subpixels = 2, int depth = 4) {
  RenderSettings st;
  st.width = 64;
  st.height = 48;
  st.subpixels = subpixels;
  st.depth = depth;
  return st;
}

bool identical(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height &&
         std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)) == 0;
}

double mean(const Image& img) {
  double s = 0;
  for (float v : img.rgb) s += v;
  return s / double(img.rgb.size());
}

TEST(Render, FeaturesOfTheDefaultSceneExcludeRefraction) {
  const Scene s = make_default_scene();
  EXPECT_EQ(s.features(), unsigned(kReflection | kSpecular | kSpheres | kPlanes | kTriangles));
  EXPECT_EQ(test::glass_scene().features(), kAllFeatures);
  Scene dark = make_default_scene();
  dark.lights.clear();
  EXPECT_FALSE(dark.features() & kSpecular);  // specular needs a light to matter
}

TEST(Render, EveryInstructionSetGivesIdenticalImages) {
  Scene no_planes = make_default_scene();
  no_planes.planes.clear();
  no_planes.plane_materials.clear();
  for (const Scene& s : {make_default_scene(), test::glass_scene(), no_planes})
    for (bool watertight : {false, true}) {
      RenderSettings st = small();
      st.watertight = watertight;
      RayCounts ra;
      const Image a = render(s, st, Schedule{Backend::serial, 1, 1}, &ra);
      EXPECT_GT(mean(a), 0.01);  // something was rendered
      for (Isa isa : test::runnable_isas()) {
        RayCounts rb;
        const Image b = render(s, st, Schedule{Backend::serial, 1, 1}, &rb, BvhConfig{}, isa);
        EXPECT_TRUE(identical(a, b)) << isa_name(isa) << " watertight " << watertight;
        EXPECT_EQ(ra.total(), rb.total());
      }
    }
}

TEST(Render, TilesRenderWithDenormalsFlushedAndTheCallersModeComesBack) {
  const Scene s = make_default_scene();
  const CompiledScene c = CompiledScene::compile(s, BvhConfig{});
  const Renderer r(c, View{s.camera, small()});
  Film film(small().width, small().height);
  RayCounts counts;
  for (bool mode : {false, true}) {
    mlib::set_flush_denormals(mode);
    r.render_tile(Tile{0, 0, small().width, 4}, 0, film, counts);
    EXPECT_EQ(mlib::flush_denormals(), mode);
  }
  mlib::set_flush_denormals(false);
}

TEST(Render, BackendsThreadCountsAndGrainsGiveIdenticalImages) {
  const Scene s = test::glass_scene();
  const Image ref = render(s, small(), Schedule{Backend::serial, 1, 1});
  for (Backend b : {Backend::omp, Backend::tbb})
    for (int threads : {1, 2, 3, 8})
      for (int grain : {1, 4, 100}) {
        const Image img = render(s, small(), Schedule{b, threads, grain});
        EXPECT_TRUE(identical(ref, img)) << backend_name(b) << " " << threads << " " << grain;
      }
}

TEST(Render, BvhLayoutDoesNotChangeTheImage) {
  const Scene s = test::glass_scene();
  const Image ref = render(s, small(1, 3), Schedule{Backend::omp, 2, 4});
  for (BvhConfig cfg : {BvhConfig{1, Split::midpoint, 16}, BvhConfig{64, Split::sah, 8},
                        BvhConfig{1u << 20, Split::sah, 16}}) {
    const Image img = render(s, small(1, 3), Schedule{Backend::omp, 2, 4}, nullptr, cfg);
    // Ties between coincident surfaces may resolve differently; nearly all pixels agree.
    std::size_t differ = 0;
    for (std::size_t i = 0; i < img.rgb.size(); ++i) differ += img.rgb[i] != ref.rgb[i];
    EXPECT_LE(differ, img.rgb.size() / 1000);
  }
}

TEST(Render, PrimaryRayCountIsPixelsTimesSubpixels) {
  const Scene s = make_default_scene();
  for (int n : {1, 3, 7}) {
    RayCounts rays;
    render(s, small(n, 2), Schedule{Backend::omp, 2, 2}, &rays);
    EXPECT_EQ(rays.primary, 64u * 48u * unsigned(n));
    EXPECT_GT(rays.reflection, 0u);  // mirrors reflect
    EXPECT_EQ(rays.refraction, 0u);  // no glass in the default scene
    EXPECT_GT(rays.shadow, 0u);
  }
}

TEST(Render, DepthZeroTracesOnlyPrimaryAndShadowRays) {
  RayCounts rays;
  render(test::glass_scene(), small(1, 0), Schedule{Backend::serial, 1, 1}, &rays);
  EXPECT_EQ(rays.reflection + rays.refraction, 0u);
}

TEST(Render, EveryPixelIsFiniteAndNonNegative) {
  const Image img = render(test::glass_scene(), small(3, 6), Schedule{Backend::tbb, 2, 4});
  for (float v : img.rgb) {
    ASSERT_TRUE(std::isfinite(v));
    ASSERT_GE(v, 0.0f);
  }
}

TEST(Render, MoreSubpixelsChangeEdgesOnly) {
  const Scene s = make_default_scene();
  const Image one = render(s, small(1, 1), Schedule{Backend::omp, 2, 4});
  const Image many = render(s, small(9, 1), Schedule{Backend::omp, 2, 4});
  EXPECT_NEAR(mean(one), mean(many), 0.02);
  EXPECT_FALSE(identical(one, many));
}

TEST(Render, ScheduleRejectsAbsurdThreadsAndGrain) {
  const Scene s = make_default_scene();
  const CompiledScene c = CompiledScene::compile(s, BvhConfig{});
  const Renderer r(c, View{s.camera, small()});
  Image img;
  EXPECT_THROW(render_frame(r, Schedule{Backend::omp, -1, 1}, img), Error);
  EXPECT_THROW(render_frame(r, Schedule{Backend::omp, 2, 0}, img), Error);
  EXPECT_THROW(render_frame(r, Schedule{Backend::omp, 5000, 1}, img), Error);
  EXPECT_THROW(parse_backend("cuda"), Error);
}

TEST(Render, SettingsRejectAbsurdValues) {
  const auto bad = [](auto edit) {
    RenderSettings st;
    edit(st);
    EXPECT_THROW(st.validate(), Error);
  };
  bad([](RenderSettings& s) { s.width = 0; });
  bad([](RenderSettings& s) { s.height = -5; });
  bad([](RenderSettings& s) { s.width = 100000; });
  bad([](RenderSettings& s) { s.subpixels = 0; });
  bad([](RenderSettings& s) { s.depth = -1; });
  bad([](RenderSettings& s) { s.min_weight = std::nanf(""); });
  bad([](RenderSettings& s) { s.min_weight = 2.0f; });
  EXPECT_THROW(check_image_fits(65535, 65535), Error);  // 48 GiB > the machine
  EXPECT_NO_THROW(check_image_fits(1920, 1080));
}

TEST(Render, ExtraLightsArePlacedDeterministicallyAfterTheScenesOwn) {
  Scene a = make_default_scene(), b = make_default_scene();
  const vec4 first = a.lights[0].position;
  set_light_count(a, 5);
  set_light_count(b, 5);
  ASSERT_EQ(a.lights.size(), 5u);
  EXPECT_EQ(a.lights[0].position, first);
  for (std::size_t i = 0; i < 5; ++i) EXPECT_EQ(a.lights[i].position, b.lights[i].position);
  for (std::size_t i = 1; i < 5; ++i) EXPECT_GT(a.lights[i].position[1], 0.0f);  // above
  set_light_count(a, 0);
  EXPECT_TRUE(a.lights.empty());
}

}  // namespace
}  // namespace rt2
