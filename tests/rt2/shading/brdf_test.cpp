// The physically based BRDF (rt2/shading/brdf.h) against the properties a BRDF must have, checked
// by numerical integration: energy (white furnace), reciprocity, Fresnel's limits, the
// mirror limit of a smooth surface and the Lambert limit of a rough dielectric.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include "rt2/shading/brdf.h"
#include "rt2/shading/sampling.h"

namespace rt2 {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;
constexpr float kDeg = kPi / 180.0f;
const vec4 kUp(0.0f, 0.0f, 1.0f);
const vec4 kWhite(1.0f, 1.0f, 1.0f);

// The view direction at `theta` from the normal +z, in the xz plane.
vec4 view_at(float theta) { return vec4(std::sin(theta), 0.0f, std::cos(theta)); }

// A unit direction from polar angle theta and azimuth phi about +z.
vec4 polar(float theta, float phi) {
  return vec4(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
}

// The surface's specular lobe alone: the same F0 and alpha, no diffuse.
PbrSurface specular_only(PbrSurface s) {
  s.metallic = 1.0f;
  s.diffuse_scale = vec4();
  return s;
}

// The weight of one GGX-distributed light direction for v: f_spec cos / pdf(l) with
// pdf(l) = D(h) n·h / (4 v·h); returns false when l is below the surface.
bool specular_sample(const PbrSurface& s, const vec4& v, Point2 u, vec4& l, float& weight) {
  const vec4 h = sample_ggx_half(u, s.alpha);
  const float v_dot_h = dot(v, h);
  l = 2.0f * v_dot_h * h - v;
  if (v_dot_h <= 0.0f || l[2] <= 0.0f) return false;
  const float pdf = ggx_d(h[2], h[0] * h[0] + h[1] * h[1], s.alpha) * h[2] / (4.0f * v_dot_h);
  weight = brdf(specular_only(s), kUp, v, l)[0] * l[2] / pdf;
  return true;
}

// The directional albedo, integral of f(l, v) n·l dl (red channel): the specular lobe by
// GGX importance sampling, the rest (the diffuse) by cosine-weighted sampling, each over
// n Hammersley points.
double directional_albedo(const PbrSurface& s, float theta_v, int n) {
  const vec4 v = view_at(theta_v);
  double specular = 0.0, diffuse = 0.0;
  for (int i = 0; i < n; ++i) {
    const Point2 u = hammersley(std::uint32_t(i), std::uint32_t(n));
    vec4 l;
    float w;
    if (specular_sample(s, v, u, l, w)) specular += w;
    // Cosine-weighted: pdf = cos / pi, so f cos / pdf = pi f.
    const vec4 lc = polar(std::asin(std::sqrt(u.y)), 2.0f * kPi * u.x);
    diffuse += kPi * (brdf(s, kUp, v, lc)[0] - brdf(specular_only(s), kUp, v, lc)[0]);
  }
  return (specular + diffuse) / n;
}

constexpr int kFurnaceSamples = 4096;

// Roughness 0.05 ... 1 in 8 steps.
float furnace_roughness(int i) { return 0.05f + 0.95f * float(i) / 7.0f; }

// The white furnace: a white surface of `metallic` reflects at most all the light, for
// every roughness of the grid and `views` view angles from 0 to max_view_degrees (within
// 2e-3: the sampling errors of this integral and of brdf_lut.h's table, ~1e-3 each at 89
// degrees).
void expect_furnace(float metallic, float max_view_degrees, int views) {
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < views; ++j) {
      const float roughness = furnace_roughness(i);
      const float theta = max_view_degrees * kDeg * float(j) / float(views - 1);
      const double albedo = directional_albedo(pbr_surface(kWhite, metallic, roughness), theta,
                                               kFurnaceSamples);
      EXPECT_LE(albedo, 1.0 + 2e-3) << "roughness " << roughness << ", view " << theta / kDeg;
    }
}

TEST(BrdfFurnace, MetalReflectsAtMostAllLight) { expect_furnace(1.0f, 89.0f, 8); }

// The text's kD = (1 - F(h·v)) (1 - metallic) fails this from about 45 degrees on (1.84 at
// roughness 0.05 and 89 degrees); brdf.h's kD, (1 - E(v))(1 - E(l)) / (1 - E_avg), holds it
// on the whole grid.
TEST(BrdfFurnace, DielectricReflectsAtMostAllLight) { expect_furnace(0.0f, 89.0f, 8); }

// A white dielectric reflects in its two terms all the light it receives, E(v) specular
// and 1 - E(v) diffuse, up to the table's and this integral's errors: the energy the
// text's kD added at grazing angles is not bought by losing some elsewhere.
TEST(BrdfFurnace, WhiteDielectricLosesNoLight) {
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j) {
      const float theta = 85.0f * kDeg * float(j) / 7.0f;
      const double albedo = directional_albedo(pbr_surface(kWhite, 0.0f, furnace_roughness(i)),
                                               theta, kFurnaceSamples);
      EXPECT_NEAR(albedo, 1.0, 0.01) << "roughness " << furnace_roughness(i) << ", view "
                                     << theta / kDeg;
    }
}

TEST(Brdf, IsReciprocal) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int k = 0; k < 2000; ++k) {
    const PbrSurface s = pbr_surface(vec4(unit(rng), unit(rng), unit(rng)), unit(rng), unit(rng));
    const vec4 v = polar(std::acos(unit(rng)), 2.0f * kPi * unit(rng));
    const vec4 l = polar(std::acos(unit(rng)), 2.0f * kPi * unit(rng));
    const vec4 f_vl = brdf(s, kUp, v, l);
    const vec4 f_lv = brdf(s, kUp, l, v);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(f_vl[c], f_lv[c], 1e-5f * std::fabs(f_vl[c]));
  }
}

TEST(Brdf, IsZeroBelowTheSurface) {
  const PbrSurface s = pbr_surface(kWhite, 0.0f, 0.5f);
  const vec4 above = polar(0.3f, 0.0f), below = polar(2.0f, 1.0f);
  EXPECT_EQ(brdf(s, kUp, above, below)[0], 0.0f);
  EXPECT_EQ(brdf(s, kUp, below, above)[0], 0.0f);
  EXPECT_EQ(brdf_cos(s, kUp, below, below)[0], 0.0f);
}

TEST(Fresnel, IsF0AtNormalIncidenceAndOneAtGrazing) {
  const vec4 f0(0.04f, 0.5f, 0.95f);
  const vec4 normal = fresnel_schlick(1.0f, f0);
  const vec4 grazing = fresnel_schlick(0.0f, f0);
  const vec4 near_grazing = fresnel_schlick(1e-4f, f0);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(normal[c], f0[c]);
    EXPECT_FLOAT_EQ(grazing[c], 1.0f);
    EXPECT_NEAR(near_grazing[c], 1.0f, 1e-3f);
  }
  // cos outside [0, 1] is clamped.
  EXPECT_EQ(fresnel_schlick(1.5f, f0)[0], f0[0]);
  EXPECT_FLOAT_EQ(fresnel_schlick(-0.5f, f0)[0], 1.0f);
}

TEST(Brdf, SurfaceFollowsTheMetallicWorkflow) {
  const vec4 base(0.9f, 0.5f, 0.1f);
  const PbrSurface dielectric = pbr_surface(base, 0.0f, 0.0f);
  const PbrSurface metal = pbr_surface(base, 1.0f, 0.5f);
  EXPECT_FLOAT_EQ(dielectric.f0[1], 0.04f);
  EXPECT_FLOAT_EQ(metal.f0[0], 0.9f);
  EXPECT_FLOAT_EQ(metal.alpha, 0.25f);
  EXPECT_EQ(dielectric.alpha, kMinAlpha);  // roughness 0 keeps a finite highlight
  EXPECT_EQ(dielectric.roughness, 0.0f);
}

// The share of the specular lobe's reflected energy within 5 degrees of the mirror
// direction, for a metal seen at 30 degrees.
double mirror_cone_fraction(float roughness) {
  const PbrSurface s = pbr_surface(kWhite, 1.0f, roughness);
  const vec4 v = view_at(30.0f * kDeg);
  const vec4 mirror(-v[0], -v[1], v[2]);
  const float cos_cone = std::cos(5.0f * kDeg);
  double inside = 0.0, total = 0.0;
  constexpr int kN = 1 << 14;
  for (int i = 0; i < kN; ++i) {
    vec4 l;
    float w;
    if (!specular_sample(s, v, hammersley(std::uint32_t(i), kN), l, w)) continue;
    total += w;
    if (float(dot(l, mirror)) >= cos_cone) inside += w;
  }
  return inside / total;
}

TEST(Brdf, SmoothLobeConvergesToTheMirrorDirection) {
  const double rough = mirror_cone_fraction(0.3f);
  const double smoother = mirror_cone_fraction(0.15f);
  const double smooth = mirror_cone_fraction(0.05f);
  EXPECT_LT(rough, smoother);
  EXPECT_LT(smoother, smooth);
  EXPECT_GE(smooth, 0.9);
}

// At roughness 1 GGX's D is 1 / pi everywhere, and a dielectric's specular lobe
// (F0 = 0.04) is weak: f pi = (1 - F) + F pi D V, with F between 0.04 and 0.07 and pi D V
// between ~0.25 and ~1 for angles up to 60 degrees, so f pi stays within [0.93, 1] of
// Lambert's 1 (6 % tolerance).
TEST(Brdf, RoughDielectricIsCloseToLambert) {
  const PbrSurface s = pbr_surface(kWhite, 0.0f, 1.0f);
  for (int i = 0; i <= 6; ++i)
    for (int j = 0; j <= 6; ++j)
      for (int k = 0; k < 8; ++k) {
        const vec4 v = polar(10.0f * kDeg * float(i), 0.0f);
        const vec4 l = polar(10.0f * kDeg * float(j), 2.0f * kPi * float(k) / 8.0f);
        EXPECT_NEAR(kPi * brdf(s, kUp, v, l)[0], 1.0f, 0.06f)
            << "view " << 10 * i << ", light " << 10 * j << ", azimuth " << 45 * k;
      }
  // Its directional albedo: 1 less the ~3 % the Fresnel takes from the diffuse and
  // GGX's single scattering does not give back.
  for (int i = 0; i <= 6; ++i)
    EXPECT_NEAR(directional_albedo(s, 10.0f * kDeg * float(i), kFurnaceSamples), 1.0, 0.04)
        << "view " << 10 * i;
}

}  // namespace
}  // namespace rt2
