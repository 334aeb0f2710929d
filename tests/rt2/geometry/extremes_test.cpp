// Numerics at the scene-scale extremes and parameters at their limits.
//
// Acne and lost refraction: a lit plane and a glass sphere of refractive index 1 (so the
// sphere must be invisible) at scales 1e-3, 1, 1e3, 1e5 and translated by 1e6. With no
// ambient light and a blue sky, a plane pixel is black only if its shadow ray hit the plane
// itself ("acne"); and the image with the sphere must equal the image without it, or a
// refracted ray got stuck at its own surface ("lost refraction"). Counts are printed.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>

#include "rt2/scene/builtin_scene.h"
#include "rt2/geometry/offset.h"
#include "rt2/render/schedule.h"
#include "tests/rt2/test_util.h"

namespace rt2 {
namespace {

struct Frame {
  Image image;
  RayCounts rays;
};

Frame render(const Scene& scene, const RenderSettings& st, Schedule sched = {Backend::omp, 0, 4}) {
  Frame f;
  FrameResult fr;
  f.image = test::render_scene(scene, st, sched, BvhConfig{}, best_isa(), &fr);
  f.rays = fr.rays;
  return f;
}

Scene plane_and_glass(float s, const vec4& shift, bool sphere, bool recenter) {
  Scene sc;
  sc.ambient = vec4(0, 0, 0);
  sc.background = vec4(0, 0, 1);
  Material floor;
  floor.ambient = vec4(0, 0, 0);
  floor.diffuse = vec4(0.8f, 0.8f, 0.8f);
  Material glass;
  glass.ambient = glass.diffuse = vec4(0, 0, 0);
  glass.transparency = 1.0f;
  glass.ior = 1.0f;
  sc.add_material("floor", floor);
  sc.add_material("glass", glass);
  sc.planes.push_back(Plane{vec4(0, 1, 0), -shift[1]});
  sc.plane_materials.push_back(0);
  if (sphere) {
    sc.spheres.push_back(Sphere{shift + vec4(0.2f, 1.0f, 0.0f) * s, s});
    sc.sphere_materials.push_back(1);
  }
  Light l;
  l.position = shift + vec4(2, 6, 3) * s;
  sc.lights.push_back(l);
  sc.camera = Camera::look_at(shift + vec4(0, 2.5f, 6) * s, shift + vec4(0, 0.75f, 0) * s,
                              vec4(0, 1, 0), 40.0f);
  if (recenter) recenter_on_camera(sc);
  return sc;
}

struct Defects {
  std::size_t acne = 0, lost = 0;
};

Defects defects(float s, const vec4& shift, bool recenter) {
  RenderSettings st;
  st.width = 96;
  st.height = 72;
  st.depth = 8;
  st.min_weight = 0.0f;
  const Image plain = render(plane_and_glass(s, shift, false, recenter), st).image;
  const Image glass = render(plane_and_glass(s, shift, true, recenter), st).image;
  Defects d;
  for (std::size_t i = 0; i < plain.rgb.size(); i += 3) {
    d.acne += plain.rgb[i] == 0.0f && plain.rgb[i + 1] == 0.0f && plain.rgb[i + 2] == 0.0f;
    float diff = 0.0f;
    for (int c = 0; c < 3; ++c) diff = std::max(diff, std::fabs(plain.rgb[i + c] - glass.rgb[i + c]));
    d.lost += diff > 2e-3f;
  }
  std::printf("scale %g, shift %g, %s: %zu acne pixels, %zu pixels changed by an invisible "
              "sphere (of %zu)\n",
              s, shift[0], recenter ? "recentred" : "world coordinates", d.acne, d.lost,
              plain.rgb.size() / 3);
  return d;
}

// offset_ray_origin (one SIMD pass) against Wächter and Binder's formula coordinate by
// coordinate, as rt2 computed it before: bit for bit, with w = 0, for points from denormal
// to float max (either side of the 1/32 x scale switch), unit and odd normals (NaN and
// infinite ones give the cast's integer indefinite), several scene scales.
TEST(Offset, EqualsThePerCoordinateFormulaBitForBitFromTinyToFarAndAtNanNormals) {
  const auto oracle = [](const vec4& p, const vec4& n, float scale) {
    const float origin = scale / 32.0f, float_scale = scale / 65536.0f;
    float out[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    for (int i = 0; i < 3; ++i) {
      const float k = 256.0f * n[i];
      const std::int32_t of =
          k >= -2147483648.0f && k < 2147483648.0f ? static_cast<std::int32_t>(k) : INT32_MIN;
      const auto bits = std::bit_cast<std::uint32_t>(p[i]);
      const auto u = static_cast<std::uint32_t>(of);
      const float moved = std::bit_cast<float>(bits + (p[i] < 0.0f ? 0u - u : u));
      out[i] = std::fabs(p[i]) < origin ? p[i] + float_scale * n[i] : moved;
    }
    return vec4(out[0], out[1], out[2], out[3]);
  };
  const auto same = [](const vec4& a, const vec4& b) {
    for (int i = 0; i < 4; ++i)
      if (std::bit_cast<std::uint32_t>(a[i]) != std::bit_cast<std::uint32_t>(b[i])) return false;
    return true;
  };
  std::mt19937 rng(36);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::uniform_int_distribution<int> e(-149, 127);
  const float scales[] = {1e-3f, 1.0f, 30.0f, 1e5f};
  for (int r = 0; r < 20000; ++r) {
    const vec4 p(std::ldexp(u(rng), e(rng)), std::ldexp(u(rng), e(rng) / 4), u(rng) * 100.0f);
    const vec4 n = normalize(vec4(u(rng), u(rng), u(rng)));
    const float scale = scales[r % 4];
    const vec4 got = offset_ray_origin(p, n, scale);
    ASSERT_TRUE(same(got, oracle(p, n, scale))) << str(p) << " " << str(n) << " " << scale;
  }
  volatile float odd[] = {std::nanf(""), INFINITY, -INFINITY, 0.0f, -0.0f, 1e38f, -3.4e38f,
                          1e-45f, 0.03125f, -0.03125f};
  for (const float a : odd)
    for (const float b : odd) {
      const vec4 p(a, b, -a), n(b, a, 0.5f);
      ASSERT_TRUE(same(offset_ray_origin(p, n, 1.0f), oracle(p, n, 1.0f))) << a << " " << b;
    }
}

TEST(Acne, NoSelfShadowingAndNoLostRefractionFromMillimetresToHundredsOfKilometres) {
  for (float s : {1e-3f, 1.0f, 1e3f, 1e5f}) {
    const Defects d = defects(s, vec4(0, 0, 0), true);
    EXPECT_EQ(d.acne, 0u) << "scale " << s;
    EXPECT_EQ(d.lost, 0u) << "scale " << s;
  }
}

TEST(Acne, NoSelfShadowingAndNoLostRefractionAMillionUnitsFromTheOrigin) {
  for (float s : {1.0f, 1e3f}) {
    const Defects d = defects(s, vec4(1e6f, 1e6f, 1e6f), true);
    EXPECT_EQ(d.acne, 0u) << "scale " << s;
    EXPECT_EQ(d.lost, 0u) << "scale " << s;
  }
  // For the record: the same far scene in world coordinates (what recentring avoids).
  defects(1.0f, vec4(1e6f, 1e6f, 1e6f), false);
}

TEST(Acne, RecentringDoesNotChangeAnImageNearTheOrigin) {
  RenderSettings st;
  st.width = 64;
  st.height = 48;
  Scene world = make_default_scene();
  Scene moved = world;
  recenter_on_camera(moved);
  EXPECT_EQ(moved.camera.position(), vec4(0, 0, 0));
  const Image a = render(world, st).image, b = render(moved, st).image;
  std::size_t differ = 0;
  for (std::size_t i = 0; i < a.rgb.size(); ++i) differ += std::fabs(a.rgb[i] - b.rgb[i]) > 1e-3f;
  EXPECT_LE(differ, a.rgb.size() / 500);  // rounding may move a few edge pixels
}

// --- parameters at their limits ----------------------------------------------------------
Scene facing_mirrors() {
  Scene sc;
  sc.ambient = vec4(0, 0, 0);
  Material mirror;
  mirror.ambient = mirror.diffuse = vec4(0, 0, 0);
  mirror.reflectivity = 1.0f;
  sc.add_material("mirror", mirror);
  sc.planes = {Plane{vec4(0, 1, 0), 0.0f}, Plane{vec4(0, -1, 0), 1.0f}};  // y = 0 and y = 1
  sc.plane_materials = {0, 0};
  sc.camera = Camera::look_at(vec4(0, 0.5f, 0), vec4(0, -1, 0), vec4(0, 0, -1), 1.0f);
  return sc;
}

TEST(Extremes, DepthTenThousandBetweenFacingMirrorsNeedsNoDeepStack) {
  RenderSettings st;
  st.width = st.height = 1;
  st.min_weight = 0.0f;
  st.depth = 10000;
  const Frame f = render(facing_mirrors(), st, Schedule{Backend::serial, 1, 1});
  EXPECT_EQ(f.rays.reflection, 10000u);  // every bounce traced, iteratively
  EXPECT_TRUE(std::isfinite(f.image.rgb[0]));
  st.depth = 0;
  EXPECT_EQ(render(facing_mirrors(), st).rays.reflection, 0u);
}

TEST(Extremes, ThousandTwentyFourSubpixelsAverageToWithinAnUlp) {
  // Nothing in view: every sample is the background; the mean must be the background.
  Scene empty;
  empty.background = vec4(0.3f, 0.7f, 0.1f);
  RenderSettings st;
  st.width = st.height = 2;
  st.subpixels = 1024;
  for (Pattern p : {Pattern::grid, Pattern::circle}) {
    st.pattern = p;
    const Image img = render(empty, st).image;
    for (int i = 0; i < 4; ++i) {
      EXPECT_NEAR(img.rgb[3 * i + 0], 0.3f, 6e-8f);
      EXPECT_NEAR(img.rgb[3 * i + 1], 0.7f, 6e-8f);
      EXPECT_NEAR(img.rgb[3 * i + 2], 0.1f, 1.5e-8f);
    }
  }
}

TEST(Extremes, ThousandTwentyFourSubpixelsResolveAnEdgeThroughThePixelCentre) {
  // A rectangle covering x < 0 in front of the camera: the 32 x 32 grid puts 512 samples on
  // each side of the edge, so the pixel is exactly the mean of the two colours.
  Scene sc;
  sc.ambient = vec4(1, 1, 1);
  sc.background = vec4(0.2f, 0.4f, 0.6f);
  Material flat;
  flat.ambient = vec4(0.9f, 0.5f, 0.1f);
  sc.add_material("flat", flat);
  Mesh rect;
  rect.positions = {vec4(-100, -100, -5), vec4(0, -100, -5), vec4(0, 100, -5), vec4(-100, 100, -5)};
  rect.faces = {{0, 1, 2}, {0, 2, 3}};
  rect.face_materials = {0, 0};
  sc.meshes.push_back(rect);
  sc.camera = Camera::look_at(vec4(0, 0, 0), vec4(0, 0, -1), vec4(0, 1, 0), 10.0f);
  RenderSettings st;
  st.width = st.height = 1;
  st.subpixels = 1024;
  const Image img = render(sc, st).image;
  EXPECT_NEAR(img.rgb[0], (0.9f + 0.2f) / 2, 1e-6f);
  EXPECT_NEAR(img.rgb[1], (0.5f + 0.4f) / 2, 1e-6f);
  EXPECT_NEAR(img.rgb[2], (0.1f + 0.6f) / 2, 1e-6f);
}

TEST(Extremes, TenThousandLightsAndNoLightsBothRender) {
  Scene many = make_default_scene();
  set_light_count(many, 10000);
  RenderSettings st;
  st.width = 8;
  st.height = 6;
  const Frame lit = render(many, st);
  EXPECT_GT(lit.rays.shadow, 10000u);
  Scene none = make_default_scene();
  set_light_count(none, 0);
  const Frame dark = render(none, st);
  EXPECT_EQ(dark.rays.shadow, 0u);
  double sum_lit = 0, sum_dark = 0;
  for (float v : lit.image.rgb) sum_lit += v;
  for (float v : dark.image.rgb) sum_dark += v;
  EXPECT_GT(sum_lit, sum_dark);
  EXPECT_GT(sum_dark, 0.0);  // ambient only: a point hidden from every light is not black
}

TEST(Extremes, OnePixelImagesAndEveryThreadCountUpToSixtyFourGiveTheSameResult) {
  const Scene sc = make_default_scene();
  RenderSettings one;
  one.width = one.height = 1;
  EXPECT_EQ(render(sc, one).image.rgb.size(), 3u);
  RenderSettings st;
  st.width = 40;
  st.height = 30;
  const Image ref = render(sc, st, Schedule{Backend::serial, 1, 1}).image;
  for (Backend b : {Backend::omp, Backend::tbb})
    for (int t : {1, 2, 5, 16, 64})
      EXPECT_EQ(render(sc, st, Schedule{b, t, 1}).image.rgb, ref.rgb) << backend_name(b) << t;
}

TEST(Extremes, WatertightAndFastKernelsRenderTheSameScene) {
  RenderSettings st;
  st.width = 64;
  st.height = 48;
  const Image fast = render(make_default_scene(), st).image;
  st.watertight = true;
  const Image tight = render(make_default_scene(), st).image;
  std::size_t differ = 0;
  for (std::size_t i = 0; i < fast.rgb.size(); ++i) differ += std::fabs(fast.rgb[i] - tight.rgb[i]) > 1e-3f;
  EXPECT_LE(differ, fast.rgb.size() / 200);  // only pixels whose rays graze an edge
}

}  // namespace
}  // namespace rt2
