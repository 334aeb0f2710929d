// Physically based shading in the render kernel (rt2/kernel/): rendered pixels against the
// formulas evaluated independently here, in double precision, and the properties the
// Whitted recursion must keep with Fresnel-weighted rays.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "tests/rt2/test_util.h"

namespace rt2 {
namespace {

constexpr double kPi = std::numbers::pi;

struct D3 {
  double x, y, z;
};
D3 operator-(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 operator+(D3 a, D3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
D3 operator*(D3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 unit(D3 a) { return a * (1.0 / std::sqrt(dot(a, a))); }
D3 d3(const vec4& v) { return {v[0], v[1], v[2]}; }

double ggx_alpha(double roughness) { return std::max(roughness * roughness, 0.002); }

// The specular lobe D V F (GGX, height-correlated Smith, Schlick with F0 = f0) times n·l,
// at n = +z, from the glTF 2.0 specification's appendix B (not from rt2/shading/brdf.h).
double reference_specular_cos(double f0, double alpha, D3 v, D3 l) {
  const D3 n{0, 0, 1};
  const double nl = dot(n, l), nv = dot(n, v);
  if (nl <= 0 || nv <= 0) return 0;
  const D3 h = unit(v + l);
  const double nh = dot(n, h), vh = dot(v, h);
  const double a2 = alpha * alpha;
  const double d = a2 / (kPi * std::pow(nh * nh * (a2 - 1) + 1, 2));
  const double vis = 0.5 / (nl * std::sqrt(nv * nv * (1 - a2) + a2) +
                            nv * std::sqrt(nl * nl * (1 - a2) + a2));
  return d * vis * (f0 + (1 - f0) * std::pow(1 - vh, 5)) * nl;
}

// The lobe's directional albedo E(mu) = integral of D V F n·l over the hemisphere, by the
// midpoint rule in (cos theta, phi) (finer near the normal, where a glossy lobe peaks).
double reference_albedo(double f0, double alpha, double mu) {
  const D3 v{std::sqrt(std::max(0.0, 1 - mu * mu)), 0, mu};
  constexpr int kTheta = 96, kPhi = 96;
  double sum = 0;
  for (int i = 0; i < kTheta; ++i) {
    const double c = 1 - ((i + 0.5) / kTheta) * ((i + 0.5) / kTheta);  // dense near 1
    const double dc = (2 * (i + 0.5) / kTheta) / kTheta;
    const double s = std::sqrt(std::max(0.0, 1 - c * c));
    for (int j = 0; j < kPhi; ++j) {
      const double phi = 2 * kPi * (j + 0.5) / kPhi;
      sum += reference_specular_cos(f0, alpha, v, {s * std::cos(phi), s * std::sin(phi), c}) *
             dc * (2 * kPi / kPhi);
    }
  }
  return sum;
}

// The BRDF of rt2/shading/brdf.h's header, f = kD base / pi + D V F with the
// energy-conserving kD = (1 - metallic)(1 - E(v))(1 - E(l)) / (1 - E_avg), times n·l, for one
// channel; E by reference_albedo and E_avg by reference_average_albedo, independently of
// rt2/shading/brdf_lut.h's table.
double reference_average_albedo(double f0, double alpha) {
  double e_avg = 0;
  constexpr int kMu = 32;
  for (int i = 0; i < kMu; ++i) {
    const double mu = (i + 0.5) / kMu;
    e_avg += 2 * reference_albedo(f0, alpha, mu) * mu / kMu;
  }
  return e_avg;
}

double reference_brdf_cos(double base, double metallic, double roughness, double e_avg, D3 n,
                          D3 v, D3 l) {
  const double nl = dot(n, l), nv = dot(n, v);
  if (nl <= 0 || nv <= 0) return 0;
  // the directions in a frame with n = +z
  const D3 a = std::fabs(n.x) < 0.9 ? D3{1, 0, 0} : D3{0, 1, 0};
  const D3 t = unit(a - n * dot(n, a));
  const D3 b{n.y * t.z - n.z * t.y, n.z * t.x - n.x * t.z, n.x * t.y - n.y * t.x};
  const auto local = [&](D3 w) { return D3{dot(w, t), dot(w, b), dot(w, n)}; };
  const double alpha = ggx_alpha(roughness);
  const double f0 = 0.04 * (1 - metallic) + base * metallic;
  const double kd = (1 - metallic) * (1 - reference_albedo(f0, alpha, nv)) *
                    (1 - reference_albedo(f0, alpha, nl)) / (1 - e_avg);
  return kd * base / kPi * nl + reference_specular_cos(f0, alpha, local(v), local(l));
}

struct SphereSetup {
  Scene scene;
  Light light;
};

// A physically based sphere of radius 1 at the origin, one light, no ambient light, seen
// from +z.
SphereSetup pbr_sphere(float metallic, float roughness) {
  SphereSetup s;
  Material m;
  m.model = Shading::pbr;
  m.base_color = vec4(0.8f, 0.5f, 0.3f);
  m.metallic = metallic;
  m.roughness = roughness;
  s.scene.add_material("pbr", m);
  s.scene.spheres.push_back(Sphere{vec4(0, 0, 0), 1.0f});
  s.scene.sphere_materials.push_back(0);
  s.scene.ambient = vec4(0, 0, 0);
  s.scene.background = vec4(0, 0, 0);
  s.light.position = vec4(3, 4, 5);
  s.light.color = vec4(1.0f, 0.9f, 0.8f);
  s.light.intensity = 2.0f;
  s.scene.lights.push_back(s.light);
  s.scene.camera = Camera::look_at(vec4(0, 0, 4), vec4(0, 0, 0), vec4(0, 1, 0), 40.0f);
  return s;
}

// Every pixel whose centre ray meets the sphere well inside its outline and the lit side
// matches the reference evaluation at the analytic hit point.
void expect_sphere_matches_reference(float metallic, float roughness) {
  const SphereSetup s = pbr_sphere(metallic, roughness);
  RenderSettings st;
  st.width = st.height = 24;
  st.depth = 0;
  const Image img = test::render_scene(s.scene, st);
  const Material& m = s.scene.materials[0];
  double e_avg[3];
  for (int ch = 0; ch < 3; ++ch)
    e_avg[ch] = reference_average_albedo(0.04 * (1 - metallic) + m.base_color[ch] * metallic,
                                         ggx_alpha(roughness));
  int checked = 0;
  for (int y = 0; y < st.height; ++y)
    for (int x = 0; x < st.width; ++x) {
      const Ray r = s.scene.camera.ray(float(x) + 0.5f, float(y) + 0.5f, st.width, st.height);
      const D3 o = d3(r.org), d = unit(d3(r.dir));
      const double b = dot(o, d), c = dot(o, o) - 1.0, disc = b * b - c;
      const std::size_t i = 3 * (std::size_t(y) * std::size_t(st.width) + std::size_t(x));
      if (disc <= 0) {
        EXPECT_EQ(img.rgb[i], 0.0f) << x << "," << y;  // a miss: the black background
        continue;
      }
      const D3 p = o + d * (-b - std::sqrt(disc));
      const D3 n = unit(p), v = d * -1.0, l = unit(d3(s.light.position) - p);
      if (dot(n, v) < 0.2 || dot(n, l) < 0.05) continue;  // outline and terminator
      for (int ch = 0; ch < 3; ++ch) {
        const double radiance = double(s.light.color[ch]) * s.light.intensity;
        const double want =
            reference_brdf_cos(m.base_color[ch], metallic, roughness, e_avg[ch], n, v, l) * radiance;
        EXPECT_NEAR(img.rgb[i + std::size_t(ch)], want, 5e-3 * want + 1e-5)
            << "pixel " << x << "," << y << " channel " << ch;
      }
      ++checked;
    }
  EXPECT_GT(checked, 50);
}

TEST(PbrShading, LitSphereMatchesTheAnalyticBrdfAtEveryPixelDielectricRough) {
  expect_sphere_matches_reference(0.0f, 0.6f);
}
TEST(PbrShading, LitSphereMatchesTheAnalyticBrdfAtEveryPixelMetalGlossy) {
  expect_sphere_matches_reference(1.0f, 0.25f);
}
TEST(PbrShading, LitSphereMatchesTheAnalyticBrdfAtEveryPixelHalfMetalMatte) {
  expect_sphere_matches_reference(0.5f, 1.0f);
}

// Under a uniform environment of radiance c (the scene's ambient colour without an
// environment) and no lights, a rough white dielectric reflects c times its split-sum
// albedo: never more than c (energy), and close to it (kD + specular ~ 1).
TEST(PbrShading, UniformAmbientLightIsReflectedWithoutGainingEnergy) {
  SphereSetup s = pbr_sphere(0.0f, 1.0f);
  s.scene.lights.clear();
  s.scene.materials[0].base_color = vec4(1, 1, 1);
  s.scene.ambient = vec4(0.5f, 0.5f, 0.5f);
  RenderSettings st;
  st.width = st.height = 16;
  st.depth = 0;
  const Image img = test::render_scene(s.scene, st);
  const std::size_t centre = 3 * (8 * 16 + 8);
  EXPECT_LE(img.rgb[centre], 0.5f * 1.001f);
  EXPECT_GT(img.rgb[centre], 0.5f * 0.9f);
}

// Smooth surfaces send a mirror ray weighted by Fresnel; rough ones take the environment
// instead and send none.
TEST(PbrShading, OnlySmoothSurfacesSpawnMirrorRays) {
  for (const float roughness : {0.0f, 0.5f}) {
    SphereSetup s = pbr_sphere(1.0f, roughness);
    s.scene.spheres.push_back(Sphere{vec4(0, 0, 3.5f), 0.2f});  // something to reflect
    s.scene.sphere_materials.push_back(0);
    RenderSettings st;
    st.width = st.height = 16;
    st.depth = 2;
    FrameResult fr;
    test::render_scene(s.scene, st, {Backend::serial, 1, 1}, {}, best_isa(), &fr);
    if (roughness == 0.0f)
      EXPECT_GT(fr.rays.reflection, 0u);
    else
      EXPECT_EQ(fr.rays.reflection, 0u);
  }
}

// A smooth metal's mirror ray carries F(n·v) per channel: looking straight at a white
// background through a roughness-0 metal of base colour b gives about b times it (Schlick
// at normal incidence is F0 = b).
TEST(PbrShading, SmoothMetalTintsItsReflectionByTheBaseColourAtNormalIncidence) {
  SphereSetup s = pbr_sphere(1.0f, 0.0f);
  s.scene.lights.clear();
  s.scene.background = vec4(1, 1, 1);
  RenderSettings st;
  st.width = st.height = 15;
  st.depth = 1;
  st.min_weight = 0.0f;
  const Image img = test::render_scene(s.scene, st);
  const std::size_t centre = 3 * (7 * 15 + 7);
  EXPECT_NEAR(img.rgb[centre + 0], 0.8f, 2e-3f);
  EXPECT_NEAR(img.rgb[centre + 1], 0.5f, 2e-3f);
  EXPECT_NEAR(img.rgb[centre + 2], 0.3f, 2e-3f);
}

// At the depth limit a mirror cannot spawn its ray: it shows the prefiltered environment
// instead (here a uniform one, the ambient colour), tinted by Fresnel, not black. One
// level deeper it shows the background through its ray; both are close to F0 times the
// light from there.
TEST(PbrShading, SmoothMetalAtTheDepthLimitShowsTheEnvironmentNotBlack) {
  SphereSetup s = pbr_sphere(1.0f, 0.0f);
  s.scene.lights.clear();
  s.scene.ambient = vec4(1, 1, 1);     // the uniform environment
  s.scene.background = vec4(1, 1, 1);  // what the mirror ray sees
  RenderSettings st;
  st.width = st.height = 15;
  st.min_weight = 0.0f;
  const std::size_t centre = 3 * (7 * 15 + 7);
  for (const int depth : {0, 1}) {
    st.depth = depth;
    const Image img = test::render_scene(s.scene, st);
    EXPECT_NEAR(img.rgb[centre + 0], 0.8f, 0.02f) << "depth " << depth;
    EXPECT_NEAR(img.rgb[centre + 2], 0.3f, 0.02f) << "depth " << depth;
  }
}

// Emission is added whatever the light.
TEST(PbrShading, EmissiveSurfaceShowsItsEmissionInTheDark) {
  SphereSetup s = pbr_sphere(0.0f, 1.0f);
  s.scene.lights.clear();
  s.scene.materials[0].emissive = vec4(0.25f, 0.5f, 2.0f);
  RenderSettings st;
  st.width = st.height = 9;
  st.depth = 0;
  const Image img = test::render_scene(s.scene, st);
  const std::size_t centre = 3 * (4 * 9 + 4);
  EXPECT_FLOAT_EQ(img.rgb[centre + 0], 0.25f);
  EXPECT_FLOAT_EQ(img.rgb[centre + 1], 0.5f);
  EXPECT_FLOAT_EQ(img.rgb[centre + 2], 2.0f);
}

// A fully transmissive dielectric lets the light of what is behind it through (a shadow
// ray passes it too): seen head on, the background shows through, tinted by the base
// colour and less what Fresnel reflects.
TEST(PbrShading, TransmissiveSphereShowsTheBackgroundTintedByItsBaseColour) {
  SphereSetup s = pbr_sphere(0.0f, 0.0f);
  s.scene.lights.clear();
  s.scene.materials[0].transmission = 1.0f;
  s.scene.materials[0].base_color = vec4(1.0f, 0.5f, 1.0f);
  s.scene.background = vec4(1, 1, 1);
  RenderSettings st;
  st.width = st.height = 15;
  st.depth = 6;
  st.min_weight = 0.0f;
  const Image img = test::render_scene(s.scene, st);
  const std::size_t centre = 3 * (7 * 15 + 7);
  // Red (b = 1): what the surfaces reflect (F0 = 0.04 each) and transmit adds up to all of
  // the background, no more (energy). Green (b = 0.5 per crossing): through both surfaces
  // (1 - F0)^2 b^2, plus the front reflection F0, plus a little bounced inside.
  EXPECT_LE(img.rgb[centre + 0], 1.0f + 1e-5f);
  EXPECT_GE(img.rgb[centre + 0], 0.97f);
  EXPECT_NEAR(img.rgb[centre + 1], 0.96f * 0.96f * 0.25f + 0.04f, 0.02f);
}

}  // namespace
}  // namespace rt2
