// Phong shading, shadows, reflection and refraction on analytic set-ups: one pixel looking
// at a known point, whose colour follows from the formulas by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "rt2/render/schedule.h"
#include "rt2/geometry/optics.h"
#include "tests/rt2/test_util.h"

namespace rt2 {
namespace {

constexpr float kDeg = std::numbers::pi_v<float> / 180.0f;

// A ground plane y = 0 with material `m`, seen at the origin by a 1x1-pixel camera at
// `eye`; no ambient light unless set.
Scene plane_scene(const Material& m, const vec4& eye) {
  Scene s;
  s.ambient = vec4(0, 0, 0);
  s.background = vec4(0.2f, 0.4f, 0.6f);
  s.add_material("m", m);
  s.planes.push_back(Plane{vec4(0, 1, 0), 0.0f});
  s.plane_materials.push_back(0);
  const vec4 up = std::fabs(eye[0]) + std::fabs(eye[2]) > 0 ? vec4(0, 1, 0) : vec4(0, 0, -1);
  s.camera = Camera::look_at(eye, vec4(0, 0, 0), up, 10.0f);
  return s;
}

Material matte(float kd) {
  Material m;
  m.ambient = vec4(0, 0, 0);
  m.diffuse = vec4(kd, kd, kd);
  m.specular = vec4(0, 0, 0);
  return m;
}

struct Pixel {
  vec4 color;
  RayCounts rays;
};

Pixel render_pixel(const Scene& s, int depth = 4, float min_weight = 0.0f) {
  RenderSettings st;
  st.width = st.height = 1;
  st.depth = depth;
  st.min_weight = min_weight;
  FrameResult fr;
  const Image img = test::render_scene(s, st, Schedule{Backend::serial, 1, 1}, BvhConfig{},
                                       best_isa(), &fr);
  return {vec4(img.rgb[0], img.rgb[1], img.rgb[2]), fr.rays};
}

void expect_rgb(const vec4& c, float r, float g, float b, float tol = 2e-5f) {
  EXPECT_NEAR(c[0], r, tol);
  EXPECT_NEAR(c[1], g, tol);
  EXPECT_NEAR(c[2], b, tol);
}

TEST(Shading, WithoutLightsOnlyTheAmbientTermRemains) {
  Material m = matte(0.9f);
  m.ambient = vec4(0.5f, 0.25f, 1.0f);
  Scene s = plane_scene(m, vec4(0, 5, 0));
  s.ambient = vec4(0.2f, 0.2f, 0.2f);
  expect_rgb(render_pixel(s).color, 0.1f, 0.05f, 0.2f);  // Ka * I_amb
}

TEST(Shading, DiffuseFollowsLambertsCosineLaw) {
  for (float angle : {0.0f, 30.0f, 60.0f, 85.0f}) {
    Scene s = plane_scene(matte(0.5f), vec4(0, 5, 0));
    Light l;
    l.position = vec4(10 * std::sin(angle * kDeg), 10 * std::cos(angle * kDeg), 0);
    l.intensity = 2.0f;
    s.lights.push_back(l);
    const float expect = 0.5f * 2.0f * std::cos(angle * kDeg);  // Kd I (L·N)
    expect_rgb(render_pixel(s).color, expect, expect, expect, 1e-4f);
  }
}

TEST(Shading, LightBelowTheSurfaceContributesNothing) {
  Scene s = plane_scene(matte(0.5f), vec4(0, 5, 0));
  Light l;
  l.position = vec4(0, -3, 0);
  s.lights.push_back(l);
  expect_rgb(render_pixel(s).color, 0, 0, 0);
}

TEST(Shading, PhongSpecularPeaksInTheMirrorDirection) {
  Material m = matte(0.0f);
  m.specular = vec4(1, 1, 1);
  m.shininess = 20.0f;
  const vec4 eye(-5, 5, 0);
  Scene s = plane_scene(m, eye);
  Light l;
  l.position = vec4(5, 5, 0);  // mirror image of the eye: R = V
  s.lights.push_back(l);
  expect_rgb(render_pixel(s).color, 1, 1, 1, 1e-4f);  // Ks I (R·V)^n = 1
  // Move the light so the angle between R and V is 10 degrees: (cos 10)^20.
  s.lights[0].position = vec4(5 * std::sqrt(2.0f) * std::sin(55 * kDeg), 5 * std::sqrt(2.0f) * std::cos(55 * kDeg), 0);
  const float expect = std::pow(std::cos(10 * kDeg), 20.0f);
  expect_rgb(render_pixel(s).color, expect, expect, expect, 2e-3f);
}

TEST(Shading, ShadowedPointGetsOnlyTheAmbientColour) {
  Material m = matte(0.5f);
  m.ambient = vec4(1, 1, 1);
  Scene s = plane_scene(m, vec4(3, 5, 0));
  s.ambient = vec4(0.1f, 0.1f, 0.1f);
  Light l;
  l.position = vec4(0, 10, 0);
  s.lights.push_back(l);
  s.spheres.push_back(Sphere{vec4(0, 5, 0), 1.0f});  // between the point and the light
  s.sphere_materials.push_back(0);
  const Pixel p = render_pixel(s, 0);
  expect_rgb(p.color, 0.1f, 0.1f, 0.1f);
  EXPECT_EQ(p.rays.shadow, 1u);
}

TEST(Shading, TransparentOccluderAttenuatesByKtPerSurfaceCrossed) {
  Scene s = plane_scene(matte(0.5f), vec4(3, 5, 0));
  Material glass = matte(0.0f);
  glass.transparency = 0.5f;
  glass.ior = 1.0f;
  s.add_material("glass", glass);
  Light l;
  l.position = vec4(0, 10, 0);
  s.lights.push_back(l);
  s.spheres.push_back(Sphere{vec4(0, 5, 0), 1.0f});
  s.sphere_materials.push_back(1);
  // Two crossings of a Kt = 0.5 sphere: the light arrives at 0.25.
  expect_rgb(render_pixel(s, 0).color, 0.125f, 0.125f, 0.125f);
}

TEST(Tracing, PerfectMirrorShowsTheBackgroundAndDepthZeroDoesNot) {
  Material mirror = matte(0.0f);
  mirror.reflectivity = 1.0f;
  const Scene s = plane_scene(mirror, vec4(1, 5, 0));
  const Pixel deep = render_pixel(s, 1);
  expect_rgb(deep.color, 0.2f, 0.4f, 0.6f);
  EXPECT_EQ(deep.rays.reflection, 1u);
  const Pixel flat = render_pixel(s, 0);
  expect_rgb(flat.color, 0, 0, 0);
  EXPECT_EQ(flat.rays.reflection, 0u);
}

TEST(Tracing, MinWeightStopsRaysThatWouldContributeTooLittle) {
  Material mirror = matte(0.0f);
  mirror.reflectivity = 0.5f;
  const Scene s = plane_scene(mirror, vec4(1, 5, 0));
  expect_rgb(render_pixel(s, 4, 0.4f).color, 0.1f, 0.2f, 0.3f);  // 0.5 > 0.4: traced
  const Pixel p = render_pixel(s, 4, 0.5f);                     // 0.5 <= 0.5: not traced
  expect_rgb(p.color, 0, 0, 0);
  EXPECT_EQ(p.rays.reflection, 0u);
}

TEST(Tracing, GlassSphereSeenHeadOnIsTransparentWithEnoughDepth) {
  Scene s;
  s.ambient = vec4(0, 0, 0);
  s.background = vec4(0.3f, 0.5f, 0.7f);
  Material glass = matte(0.0f);
  glass.transparency = 1.0f;
  glass.ior = 1.5f;
  s.add_material("glass", glass);
  s.spheres.push_back(Sphere{vec4(0, 0, -5), 1.0f});
  s.sphere_materials.push_back(0);
  s.camera = Camera::look_at(vec4(0, 0, 0), vec4(0, 0, -5), vec4(0, 1, 0), 1.0f);
  // Enter and leave: two refractions at normal incidence, then the background.
  const Pixel through = render_pixel(s, 2);
  expect_rgb(through.color, 0.3f, 0.5f, 0.7f, 1e-4f);
  EXPECT_EQ(through.rays.refraction, 2u);
  expect_rgb(render_pixel(s, 1).color, 0, 0, 0);  // stuck inside after one refraction
}

TEST(Optics, ReflectionKeepsTheAngleAndMirrorsTheNormalComponent) {
  const vec4 n(0, 1, 0);
  const vec4 i = normalize(vec4(1, -2, 0.5f));
  const vec4 r = reflect(i, n);
  EXPECT_NEAR(float(dot(r, n)), -float(dot(i, n)), 1e-6f);
  EXPECT_NEAR(r[0], i[0], 1e-6f);
  EXPECT_NEAR(r[2], i[2], 1e-6f);
  EXPECT_NEAR(float(dot(r, r)), 1.0f, 1e-6f);
}

TEST(Optics, RefractionFollowsSnellsLaw) {
  const vec4 n(0, 1, 0);
  for (float theta : {0.0f, 10.0f, 30.0f, 60.0f, 89.0f}) {
    const vec4 i(std::sin(theta * kDeg), -std::cos(theta * kDeg), 0);
    vec4 t;
    ASSERT_TRUE(refract(i, n, 1.0f / 1.5f, t));
    const float sin_t = std::sqrt(t[0] * t[0] + t[2] * t[2]);
    EXPECT_NEAR(sin_t, std::sin(theta * kDeg) / 1.5f, 1e-6f) << theta;  // n1 sin a = n2 sin b
    EXPECT_LT(t[1], 0.0f);     // goes into the surface
    EXPECT_GE(t[0], 0.0f);     // in the plane of incidence, same side
    EXPECT_NEAR(float(dot(t, t)), 1.0f, 1e-6f);
  }
}

TEST(Optics, TotalInternalReflectionBeyondTheCriticalAngle) {
  const vec4 n(0, 1, 0);
  const float critical = std::asin(1.0f / 1.5f) / kDeg;  // 41.8 degrees
  vec4 t;
  const auto incident = [](float deg) { return vec4(std::sin(deg * kDeg), -std::cos(deg * kDeg), 0); };
  EXPECT_TRUE(refract(incident(critical - 0.5f), n, 1.5f, t));
  EXPECT_FALSE(refract(incident(critical + 0.5f), n, 1.5f, t));
  EXPECT_FALSE(refract(incident(80.0f), n, 1.5f, t));
}

TEST(Optics, NormalIncidencePassesStraightThrough) {
  vec4 t;
  ASSERT_TRUE(refract(vec4(0, -1, 0), vec4(0, 1, 0), 1.0f / 1.33f, t));
  EXPECT_EQ(t, vec4(0, -1, 0));
}

TEST(Shading, CheckerAlternatesDiffuseColourByCell) {
  Material m;
  m.diffuse = vec4(1, 1, 1);
  m.diffuse2 = vec4(0, 0, 0);
  m.checker_scale = 1.0f;
  EXPECT_EQ(m.diffuse_at(vec4(0.5f, 0, 0.5f)), vec4(1, 1, 1));
  EXPECT_EQ(m.diffuse_at(vec4(1.5f, 0, 0.5f)), vec4(0, 0, 0));
  EXPECT_EQ(m.diffuse_at(vec4(-0.5f, 0, 0.5f)), vec4(0, 0, 0));
  EXPECT_EQ(m.diffuse_at(vec4(1.5f, 0, 1.5f)), vec4(1, 1, 1));
}

}  // namespace
}  // namespace rt2
