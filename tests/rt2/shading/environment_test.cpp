// The environment (rt2/shading/environment.h): its direction <-> uv convention, its lookups, and
// its prefiltered maps against constant and analytic environments and an independent
// integration of the split-sum table (brdf_lut.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "rt2/shading/brdf.h"
#include "rt2/shading/brdf_lut.h"
#include "rt2/shading/environment.h"
#include "rt2/base/error.h"

namespace rt2 {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;
constexpr float kDeg = kPi / 180.0f;

// Unit directions spread over the sphere (a fixed seed), the poles and the axes included.
std::vector<vec4> sphere_directions(int n) {
  std::vector<vec4> dirs = {vec4(0, 1, 0), vec4(0, -1, 0), vec4(1, 0, 0), vec4(-1, 0, 0),
                            vec4(0, 0, 1), vec4(0, 0, -1)};
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int i = 0; i < n; ++i) {
    const float z = 2.0f * unit(rng) - 1.0f, phi = 2.0f * kPi * unit(rng);
    const float r = std::sqrt(1.0f - z * z);
    dirs.push_back(vec4(r * std::cos(phi), z, r * std::sin(phi)));
  }
  return dirs;
}

// An image of w x h texels, rgb(x, y) per texel.
template <class F>
std::vector<float> make_image(int w, int h, F rgb) {
  std::vector<float> out;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const vec4 c = rgb(x, y);
      out.insert(out.end(), {c[0], c[1], c[2]});
    }
  return out;
}

void expect_relative(const vec4& got, const vec4& want, float tolerance, const char* what) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], tolerance * want[c]) << what;
}

// Every lookup of an environment that is `color` everywhere: radiance, irradiance at many
// normals, specular at every roughness level and between.
void expect_constant(const Environment& env, const vec4& color, float tolerance) {
  for (const vec4& d : sphere_directions(200)) {
    expect_relative(env.radiance(d), color, tolerance, "radiance");
    expect_relative(env.irradiance(d), color, tolerance, "irradiance");
    for (int k = 0; k <= 20; ++k)
      expect_relative(env.specular(d, float(k) / 20.0f), color, tolerance, "specular");
  }
}

// The polynomial atan2 and acos of the lookups against libm's, over their whole domains
// (every quadrant, the axes, signed zeros, |x| = 1).
TEST(Equirect, FastAtan2AndAcosMatchLibmWithin2e6Radians) {
  for (int i = -400; i <= 400; ++i) {
    const float x = float(i) / 400.0f;
    EXPECT_NEAR(fast_acos(x), std::acos(x), 1e-6f) << x;
    for (int j = -40; j <= 40; ++j) {
      const float y = float(j) / 37.0f;
      EXPECT_NEAR(fast_atan2(y, x), std::atan2(y, x), 2e-6f) << y << ", " << x;
      EXPECT_NEAR(fast_atan2(1e-30f * y, 1e-30f * x), std::atan2(1e-30f * y, 1e-30f * x),
                  2e-6f);
    }
  }
  EXPECT_EQ(fast_atan2(0.0f, 0.0f), 0.0f);
  EXPECT_NEAR(fast_atan2(0.0f, -1.0f), std::numbers::pi_v<float>, 1e-6f);
  EXPECT_NEAR(fast_atan2(-1.0f, 0.0f), -0.5f * std::numbers::pi_v<float>, 1e-6f);
}

TEST(Equirect, DirectionUvRoundTrip) {
  for (const vec4& d : sphere_directions(500)) {
    const vec4 back = uv_to_direction(direction_to_uv(d));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(back[c], d[c], 2e-5f);
  }
  // The convention: +y is the top row, -z the middle of the image, +x at u = 0.75.
  EXPECT_NEAR(direction_to_uv(vec4(0, 1, 0)).v, 0.0f, 1e-6f);
  EXPECT_NEAR(direction_to_uv(vec4(0, -1, 0)).v, 1.0f, 1e-6f);
  EXPECT_NEAR(direction_to_uv(vec4(0, 0, -1)).u, 0.5f, 1e-6f);
  EXPECT_NEAR(direction_to_uv(vec4(1, 0, 0)).u, 0.75f, 1e-6f);
  EXPECT_NEAR(direction_to_uv(vec4(-1, 0, 0)).u, 0.25f, 1e-6f);
  EXPECT_NEAR(direction_to_uv(vec4(0, 0, -1)).v, 0.5f, 1e-6f);
}

TEST(Environment, UniformReturnsItsColourExactly) {
  const vec4 color(0.25f, 1.5f, 3.0f);
  expect_constant(Environment::uniform(color), color, 1e-6f);
}

// The real prefilter path: a constant image must come out as its constant.
TEST(Environment, ConstantImagePrefiltersToItsColour) {
  const vec4 color(0.3f, 0.5f, 0.7f);
  const Environment env = Environment::from_image(
      96, 48, make_image(96, 48, [&](int, int) { return color; }), 2.0f, 30.0f);
  expect_constant(env, color * 2.0f, 1e-3f);
}

// Maps one texel wide or tall, 1 x 1, and 100,000 texels on a side (where i * side
// overflowed an int while resampling, and rows next to a pole have no solid angle in
// float): every lookup gives the constant, and no specular level is over 512 texels a side.
TEST(Environment, ThinWideAndTallImagesPrefilterToTheirColour) {
  const vec4 color(0.3f, 0.5f, 0.7f);
  for (const auto& [w, h] : {std::pair{1, 1}, std::pair{1, 7}, std::pair{7, 1},
                             std::pair{1, 100000}, std::pair{100000, 1}, std::pair{3, 30000}}) {
    SCOPED_TRACE(std::to_string(w) + " x " + std::to_string(h));
    const Environment env =
        Environment::from_image(w, h, make_image(w, h, [&](int, int) { return color; }), 1.0f, 10.0f);
    expect_constant(env, color, 1e-3f);
    for (int k = 0; k < Environment::kSpecularLevels; ++k) {
      EXPECT_LE(env.specular_map(k).width, 512) << "level " << k;
      EXPECT_LE(env.specular_map(k).height, 512) << "level " << k;
    }
  }
}

// Radiance 1 above the horizon, 0 below: E / pi on a plane tilted by beta from +y is
// (1 + cos beta) / 2 (the sky-dome view factor).
TEST(Environment, HemisphereIrradianceMatchesTheViewFactor) {
  const Environment env = Environment::from_image(
      128, 64, make_image(128, 64, [](int, int y) { return y < 32 ? vec4(1, 1, 1) : vec4(); }),
      1.0f, 0.0f);
  for (int b = 0; b <= 180; b += 15)
    for (int a = 0; a < 360; a += 45) {
      const float beta = float(b) * kDeg, azimuth = float(a) * kDeg;
      const vec4 n(std::sin(beta) * std::cos(azimuth), std::cos(beta),
                   std::sin(beta) * std::sin(azimuth));
      EXPECT_NEAR(env.irradiance(n)[1], 0.5f * (1.0f + std::cos(beta)), 0.02f)
          << "tilt " << b << ", azimuth " << a;
    }
}

// A = integral of f_spec cos with F0 = 1 less B, B = the integral with F0 = 0, integrated
// over a stratified grid of the hemisphere, uniform in cos theta and phi.
void integrate_specular(float n_dot_v, float roughness, double& with_f0_1, double& with_f0_0) {
  const vec4 n(0, 0, 1), v(std::sqrt(1.0f - n_dot_v * n_dot_v), 0.0f, n_dot_v);
  const float alpha = std::max(roughness * roughness, kMinAlpha);
  const PbrSurface one{vec4(), vec4(1, 1, 1), alpha, roughness, 1.0f, vec4()};
  const PbrSurface zero{vec4(), vec4(), alpha, roughness, 1.0f, vec4()};
  constexpr int kN = 600;
  with_f0_1 = with_f0_0 = 0.0;
  for (int i = 0; i < kN; ++i)
    for (int j = 0; j < kN; ++j) {
      const float z = (float(i) + 0.5f) / kN, phi = 2.0f * kPi * (float(j) + 0.5f) / kN;
      const float r = std::sqrt(1.0f - z * z);
      const vec4 l(r * std::cos(phi), r * std::sin(phi), z);
      with_f0_1 += brdf(one, n, v, l)[0] * z;
      with_f0_0 += brdf(zero, n, v, l)[0] * z;
    }
  const double solid_angle = 2.0 * std::numbers::pi / (double(kN) * kN);
  with_f0_1 *= solid_angle;
  with_f0_0 *= solid_angle;
}

TEST(BrdfLut, MatchesHemisphereIntegration) {
  const float points[][2] = {{0.5f, 0.5f}, {0.25f, 0.75f}, {0.8f, 0.35f}, {0.95f, 0.6f},
                             {0.6f, 1.0f}};
  for (const auto& p : points) {
    const auto [a, b] = split_sum(p[0], p[1]);
    double one, zero;
    integrate_specular(p[0], p[1], one, zero);
    EXPECT_NEAR(a + b, one, 0.02 * one) << "n.v " << p[0] << ", roughness " << p[1];
    EXPECT_NEAR(b, zero, 0.02 * one) << "n.v " << p[0] << ", roughness " << p[1];
  }
}

TEST(BrdfLut, ReflectsAtMostAllLight) {
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 40; ++j) {
      const auto [a, b] = split_sum(0.001f + 0.999f * float(i) / 40.0f, float(j) / 40.0f);
      EXPECT_GE(a, 0.0f);
      EXPECT_GE(b, 0.0f);
      EXPECT_LE(a + b, 1.0f + 1e-3f);
    }
}

TEST(Environment, RadianceReadsTheRightTexel) {
  constexpr int kW = 64, kH = 32, kX = 40, kY = 10;
  const vec4 bright(1.0f, 2.0f, 3.0f);
  const auto image = make_image(kW, kH, [&](int x, int y) {
    return x == kX && y == kY ? bright : vec4();
  });
  const Environment env = Environment::from_image(kW, kH, image, 1.0f, 0.0f);
  const vec4 centre = env.source_map().texel_direction(kX, kY);
  expect_relative(env.radiance(centre), bright, 1e-3f, "the bright texel");
  EXPECT_NEAR(env.radiance(env.source_map().texel_direction(kX + 1, kY))[2], 0.0f, 1e-3f);
  EXPECT_NEAR(env.radiance(env.source_map().texel_direction(kX, kY + 1))[2], 0.0f, 1e-3f);
  // Turned by 90 degrees about +y (+z towards +x), the texel is seen at R_y(90) centre.
  const Environment turned = Environment::from_image(kW, kH, image, 1.0f, 90.0f);
  const vec4 seen(centre[2], centre[1], -centre[0]);
  expect_relative(turned.radiance(seen), bright, 1e-3f, "the turned texel");
  EXPECT_NEAR(turned.radiance(centre)[2], 0.0f, 1e-3f);
}

TEST(Environment, FromImageValidatesItsInput) {
  EXPECT_THROW(Environment::from_image(0, 4, {}, 1.0f, 0.0f), Error);
  EXPECT_THROW(Environment::from_image(2, 1, std::vector<float>(5, 1.0f), 1.0f, 0.0f), Error);
  EXPECT_THROW(Environment::from_image(1, 1, {1, 1, 1}, -1.0f, 0.0f), Error);
  EXPECT_THROW(Environment::from_image(1, 1, {1, 1, 1}, 1.0f, kInfinity), Error);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const Environment env = Environment::from_image(2, 1, {1, nan, -2, kInfinity, 1, 1}, 1.0f, 0.0f);
  EXPECT_EQ(env.replaced_values(), 3u);
  for (const vec4& t : env.source_map().texels)
    for (int c = 0; c < 3; ++c) EXPECT_TRUE(std::isfinite(t[c]) && t[c] >= 0.0f);
}

TEST(Environment, SkyIsBrighterAboveAndBrightestAtTheSun) {
  const vec4 sun = normalize(vec4(0.5f, 0.6f, -0.4f));
  const Environment env = Environment::sky(sun, 1.0f, 0.0f);
  std::printf("  sky(): %d x %d, prefiltered in %.3f s\n", env.source_map().width,
              env.source_map().height, env.prefilter_seconds());
  const EquirectMap& map = env.source_map();
  double above = 0.0, below = 0.0;
  float brightest = -1.0f;
  vec4 brightest_dir;
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x) {
      const vec4& t = map.at(x, y);
      for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(t[c]) && t[c] >= 0.0f);
      const float sum = t[0] + t[1] + t[2];
      (y < map.height / 2 ? above : below) += sum;
      if (sum > brightest) {
        brightest = sum;
        brightest_dir = map.texel_direction(x, y);
      }
    }
  EXPECT_GT(above, 2.0 * below);
  EXPECT_GT(float(dot(brightest_dir, sun)), std::cos(3.0f * kDeg));
  EXPECT_GT(env.irradiance(vec4(0, 1, 0))[2], env.irradiance(vec4(0, -1, 0))[2]);
  EXPECT_GT(env.radiance(sun)[0], 10.0f * env.radiance(vec4(0, 1, 0))[0]);
  for (int k = 0; k <= 10; ++k)
    for (const vec4& d : sphere_directions(50)) {
      const vec4 s = env.specular(d, float(k) / 10.0f), e = env.irradiance(d);
      for (int c = 0; c < 3; ++c) EXPECT_TRUE(std::isfinite(s[c]) && s[c] >= 0.0f && e[c] >= 0.0f);
    }
  EXPECT_THROW(Environment::sky(vec4(), 1.0f, 0.0f), Error);
}

}  // namespace
}  // namespace rt2
