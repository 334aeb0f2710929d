// tests/rt2/test_util.h — fixed-seed random geometry and rays, and small scenes, shared by
// the rt2 tests.
#pragma once

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "rt2/bvh/accel.h"
#include "rt2/scene/builtin_scene.h"
#include "rt2/render/compiled_scene.h"
#include "rt2/base/isa.h"
#include "rt2/render/schedule.h"
#include "rt2/scene/scene.h"

namespace rt2::test {

// Sanitizer builds run the same tests on fewer random samples (they are much slower).
#if defined(__SANITIZE_ADDRESS__)
inline constexpr int kSampleScale = 10;
#else
inline constexpr int kSampleScale = 1;
#endif

inline vec4 random_point(std::mt19937& rng, float lo, float hi) {
  std::uniform_real_distribution<float> u(lo, hi);
  return vec4(u(rng), u(rng), u(rng));
}

inline vec4 random_direction(std::mt19937& rng) {
  std::normal_distribution<float> n(0.0f, 1.0f);
  for (;;) {
    const vec4 d(n(rng), n(rng), n(rng));
    if (float(dot(d, d)) > 1e-6f) return normalize(d);
  }
}

// n random triangles of edge length up to `size` inside [-1, 1]^3.
inline Mesh random_soup(std::size_t n, float size, unsigned seed, std::uint32_t material = 0) {
  std::mt19937 rng(seed);
  Mesh m;
  m.name = "soup";
  for (std::size_t i = 0; i < n; ++i) {
    const vec4 c = random_point(rng, -1.0f, 1.0f);
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    for (int k = 0; k < 3; ++k) m.positions.push_back(c + size * random_point(rng, -0.5f, 0.5f));
    m.faces.push_back({base, base + 1, base + 2});
    m.face_materials.push_back(material);
  }
  m.drop_degenerate();
  return m;
}

// A scene holding just geometry, one grey material and a camera; no lights.
inline Scene geometry_scene(std::vector<Mesh> meshes, std::vector<Sphere> spheres = {}) {
  Scene s;
  s.add_material("grey", Material{});
  s.meshes = std::move(meshes);
  s.spheres = std::move(spheres);
  s.sphere_materials.assign(s.spheres.size(), 0);
  return s;
}

// Rays for checking intersection code: half from random origins in random directions,
// half aimed from random origins at random points of random triangles (so most hit).
inline std::vector<Ray> random_rays(const Accel& acc, std::size_t n, unsigned seed,
                                    float spread = 3.0f) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Ray> rays;
  rays.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const vec4 org = random_point(rng, -spread, spread);
    if (i % 2 == 0 || acc.tris.empty()) {
      rays.emplace_back(org, random_direction(rng));
      continue;
    }
    const Triangle& t = acc.tris[rng() % acc.tris.size()];
    float a = u(rng), b = u(rng);
    if (a + b > 1.0f) {
      a = 1.0f - a;
      b = 1.0f - b;
    }
    const vec4 target = t.point(a, b);
    const vec4 d = target - org;
    if (float(dot(d, d)) < 1e-12f) continue;
    rays.emplace_back(org, normalize(d));
  }
  return rays;
}

// The instruction sets this build has and this CPU runs: every one is tested.
inline std::vector<Isa> runnable_isas() {
  std::vector<Isa> out;
  for (Isa isa : built_isas())
    if (isa_supported(isa)) out.push_back(isa);
  return out;
}

// The nearest hit by testing every primitive with the one-triangle tests of
// rt2/geometry/triangle.h: the oracle for the BVH. Ties at equal t go to the smaller triangle
// index (strict <, in index order), as the BVH's do.
inline Hit brute_force(const Accel& acc, const Ray& r, float t_min, float t_max,
                       bool watertight = false) {
  Hit h;
  h.t = t_max;
  const WatertightRay shear(r);
  for (std::uint32_t i = 0; i < acc.tris.size(); ++i) {
    float t, u, v;
    if (watertight ? intersect_watertight(acc.tris[i], shear, t_min, h.t, t, u, v)
                   : intersect(acc.tris[i], r, t_min, h.t, t, u, v)) {
      h.t = t;
      h.u = u;
      h.v = v;
      h.prim = kTriangleTag | i;
    }
  }
  for (std::uint32_t i = 0; i < acc.spheres.size(); ++i) {
    float t;
    if (intersect(acc.spheres[i], r, t_min, h.t, t)) {
      h.t = t;
      h.prim = kSphereTag | i;
    }
  }
  for (std::uint32_t i = 0; i < acc.planes.size(); ++i) {
    float t;
    if (intersect(acc.planes[i], r, t_min, h.t, t)) {
      h.t = t;
      h.prim = kPlaneTag | i;
    }
  }
  if (!h.found()) h.t = kInfinity;
  return h;
}

// Whether two hits are the same bits: t, u, v, the primitive and the instance.
inline bool bitwise_same(const Hit& a, const Hit& b) {
  return std::memcmp(&a.t, &b.t, sizeof a.t) == 0 && std::memcmp(&a.u, &b.u, sizeof a.u) == 0 &&
         std::memcmp(&a.v, &b.v, sizeof a.v) == 0 && a.prim == b.prim && a.instance == b.instance;
}

// The built-in scene with a glass sphere and a second light: every feature at once (glass,
// mirror, specular, spheres, a plane, triangles, lights).
inline Scene glass_scene() {
  Scene s = make_default_scene();
  Material glass;
  glass.diffuse = vec4(0.05f, 0.05f, 0.05f);
  glass.specular = vec4(0.8f, 0.8f, 0.8f);
  glass.reflectivity = 0.1f;
  glass.transparency = 0.85f;
  glass.ior = 1.5f;
  const std::uint32_t g = s.add_material("glass", glass);
  s.spheres.push_back(Sphere{vec4(-0.6f, 0.3f, 0.4f), 0.3f});
  s.sphere_materials.push_back(g);
  set_light_count(s, 2);
  return s;
}

// Renders `scene` through the whole pipeline (compile, the scene's camera, the schedule's
// tiles, every pass, the film's mean) and checks that no pixel came out NaN or infinite.
inline Image render_scene(const Scene& scene, const RenderSettings& settings,
                          const Schedule& schedule = {Backend::serial, 1, 1},
                          const BvhConfig& bvh = {}, Isa isa = best_isa(),
                          FrameResult* result = nullptr) {
  const CompiledScene compiled = CompiledScene::compile(scene, bvh, isa);
  const Renderer r(compiled, View{scene.camera, settings});
  Image image;
  const FrameResult fr = render_frame(r, schedule, image);
  EXPECT_EQ(fr.nonfinite_pixels, 0u);  // no NaN or infinity reaches a pixel
  if (result) *result = fr;
  return image;
}

}  // namespace rt2::test
