// Geometry that never leaks: closed meshes shot from inside, with rays aimed exactly at
// vertices, at edge midpoints and at random points (10^6 rays per mesh in the release
// build). The watertight test must let none escape; the fast test's escape rate is
// measured and printed (README, Robustness). Also spheres at extreme scales, ray origins on
// a sphere's surface, and rays with zero or NaN directions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>

#include "rt2/base/error.h"
#include "rt2/geometry/offset.h"
#include "rt2/io/scene_io.h"
#include "rt2/scene/shapes.h"
#include "rt2/render/trace.h"
#include "tests/rt2/test_util.h"

namespace rt2 {
namespace {

using test::kSampleScale;

constexpr TraceOptions kFast{false};
constexpr TraceOptions kTight{true};

// The vertices, the midpoints of every edge, then random points on random faces, up to n.
std::vector<vec4> targets(const Mesh& m, std::size_t n, unsigned seed) {
  std::vector<vec4> out(m.positions);
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (const auto& f : m.faces)
    for (int k = 0; k < 3; ++k) {
      const auto a = std::min(f[k], f[(k + 1) % 3]), b = std::max(f[k], f[(k + 1) % 3]);
      if (edges.insert({a, b}).second) out.push_back((m.positions[a] + m.positions[b]) * 0.5f);
    }
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  while (out.size() < n) {
    const auto& f = m.faces[rng() % m.faces.size()];
    float a = u(rng), b = u(rng);
    if (a + b > 1.0f) {
      a = 1.0f - a;
      b = 1.0f - b;
    }
    const Triangle t = Triangle::make(m.positions[f[0]], m.positions[f[1]], m.positions[f[2]]);
    out.push_back(t.point(a, b));
  }
  return out;
}

struct Escapes {
  std::size_t rays = 0, fast = 0, watertight = 0;
};

// Rays from `inside` through the mesh's vertices, edge midpoints and random points, with
// every runnable ISA (each has its own BVH width); the escapes summed over them.
Escapes shoot_from_inside(const Mesh& mesh, const vec4& inside, std::size_t n) {
  const Scene scene = test::geometry_scene({mesh});
  const std::vector<vec4> aims = targets(mesh, n, 7);
  std::vector<Ray> rays;
  rays.reserve(aims.size());
  for (const vec4& a : aims) rays.emplace_back(inside, normalize(a - inside));
  const std::vector<float> t_max(rays.size(), kInfinity);
  Escapes e;
  e.rays = rays.size();
  for (Isa isa : test::runnable_isas()) {
    const Accel acc = Accel::build(scene, BvhConfig{4, Split::sah, 16}, isa);
    std::size_t fast = 0, tight = 0;
    constexpr std::size_t kChunk = 4096;
#pragma omp parallel for reduction(+ : fast, tight) schedule(dynamic, 1)
    for (std::size_t c = 0; c < rays.size(); c += kChunk) {
      const std::size_t n_c = std::min(kChunk, rays.size() - c);
      std::vector<Hit> a(n_c), b(n_c);
      trace_closest(acc, kFast, rays.data() + c, t_max.data() + c, n_c, a.data());
      trace_closest(acc, kTight, rays.data() + c, t_max.data() + c, n_c, b.data());
      for (std::size_t i = 0; i < n_c; ++i) {
        fast += !a[i].found();
        tight += !b[i].found();
      }
    }
    std::printf("%s (%s, %d-wide BVH): %zu rays from inside, %zu vertices: fast test %zu escapes "
                "(%.2e), watertight %zu\n",
                mesh.name.c_str(), isa_name(isa), bvh_width(isa), e.rays, mesh.positions.size(),
                fast, double(fast) / double(e.rays), tight);
    e.fast += fast;
    e.watertight += tight;
  }
  return e;
}

// Parity of the crossings along a few rays (watertight, every hit counted): odd = inside.
bool is_inside(const Mesh& mesh, const vec4& p) {
  const Scene scene = test::geometry_scene({mesh});
  const Accel acc = Accel::build(scene, BvhConfig{4, Split::sah, 16});
  for (const vec4& d : {vec4(0.3f, 0.9f, 0.1f), vec4(-0.7f, 0.2f, 0.5f), vec4(0.1f, -0.4f, -0.9f)}) {
    const Ray r(p, normalize(d));
    const WatertightRay shear(r);
    int hits = 0;
    for (const Triangle& t : acc.tris) {
      float th, u, v;
      hits += intersect_watertight(t, shear, 0.0f, kInfinity, th, u, v);
    }
    if (hits % 2 == 0) return false;
  }
  return true;
}

TEST(Leak, WatertightTestLetsNoRayOutOfAClosedIcosphere) {
  const Mesh m = make_icosphere(vec4(0.1f, -0.2f, 0.3f), 1.0f, 5, 0);  // 20,480 triangles
  const Escapes e = shoot_from_inside(m, vec4(0.1f, -0.2f, 0.3f), 1'000'000 / kSampleScale);
  EXPECT_EQ(e.watertight, 0u);
}

TEST(Leak, WatertightTestLetsNoRayOutOfACubeThroughItsCornersAndEdges) {
  // 12 big triangles: every corner and every diagonal is shared; the centre sees the
  // corners along exact diagonals.
  const Mesh m = make_cube(vec4(0, 0, 0), 1.0f, 0);
  const Escapes e = shoot_from_inside(m, vec4(0, 0, 0), 1'000'000 / kSampleScale);
  EXPECT_EQ(e.watertight, 0u);
  const Escapes off = shoot_from_inside(m, vec4(0.25f, -0.125f, 0.5f), 200'000 / kSampleScale);
  EXPECT_EQ(off.watertight, 0u);
}

TEST(Leak, WatertightTestLetsNoRayOutOfTheStanfordBunny) {
  // Debian's libcgal-demo bunny (75,408 triangles, closed), fetched by scripts/fetch-meshes
  // (scripts/test runs it).
  const std::string path = std::string(RT2_SOURCE_DIR) + "/data/meshes/bunny00.obj";
  ASSERT_TRUE(std::filesystem::exists(path)) << path << " is missing: run scripts/fetch-meshes";
  Scene holder;
  Mesh m = load_obj(path, holder);
  m.name = "bunny00";
  for (auto& mat : m.face_materials) mat = 0;
  vec4 c;
  for (const vec4& p : m.positions) c += p;
  c /= float(m.positions.size());
  ASSERT_TRUE(is_inside(m, c)) << "the vertex centroid is not inside the bunny";
  const Escapes e = shoot_from_inside(m, c, 1'000'000 / kSampleScale);
  EXPECT_EQ(e.watertight, 0u);
}

TEST(Leak, BothTestsAgreeAwayFromEdges) {
  // Where a ray is far from any edge, the two tests are the same mathematics: same hit,
  // distances within rounding. Rounding grows as the ray grazes the triangle, like
  // 1 / |cos| of the angle to its normal; very grazing hits (|cos| < 0.1) are skipped.
  const Scene scene = test::geometry_scene({test::random_soup(500, 0.3f, 41)});
  const Accel acc = Accel::build(scene, BvhConfig{});
  const auto rays = test::random_rays(acc, 20000 / kSampleScale, 42);
  std::size_t differ = 0;
  for (const Ray& r : rays) {
    const Hit a = trace_closest(acc, r, kInfinity, kFast);
    const Hit b = trace_closest(acc, r, kInfinity, kTight);
    if (a.found() != b.found() || (a.found() && a.prim != b.prim)) {
      ++differ;  // only a ray within rounding of an edge may differ
      continue;
    }
    if (a.found() && prim_tag(a.prim) == kTriangleTag) {
      const Triangle& tri = acc.tris[prim_index(a.prim)];
      const float cos = std::fabs(float(dot(normalize(tri.n), r.dir)));
      if (cos < 0.1f) continue;
      EXPECT_NEAR(a.t, b.t, 2e-5f * (1.0f + a.t) / cos);
      EXPECT_NEAR(a.u, b.u, 4e-5f * (1.0f + a.t) / cos);
      EXPECT_NEAR(a.v, b.v, 4e-5f * (1.0f + a.t) / cos);
    }
  }
  EXPECT_LE(differ, rays.size() / 1000);
}

TEST(Leak, WatertightTestDecidesExactEdgeHitsConsistentlyForBothNeighbours) {
  // Two triangles sharing the edge x = 0; rays exactly through points of that edge hit
  // exactly one or both of them, never neither.
  Mesh m;
  m.positions = {vec4(0, -1, 0), vec4(0, 1, 0), vec4(-1, 0, 0), vec4(1, 0, 0)};
  m.faces = {{0, 1, 2}, {1, 0, 3}};
  m.face_materials = {0, 0};
  const Scene scene = test::geometry_scene({m});
  std::map<Isa, Accel> accs;
  for (Isa isa : test::runnable_isas()) accs[isa] = Accel::build(scene, BvhConfig{}, isa);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-0.99f, 0.99f);
  for (int i = 0; i < 10000; ++i) {
    const vec4 on_edge(0.0f, u(rng), 0.0f);
    const vec4 org = on_edge + vec4(u(rng), u(rng), 1.0f + std::fabs(u(rng)));
    for (Isa isa : test::runnable_isas())
      ASSERT_TRUE(trace_closest(accs[isa], Ray(org, normalize(on_edge - org)), kInfinity, kTight)
                      .found())
          << i << " " << isa_name(isa);
  }
}

TEST(Leak, EdgeFunctionZeroInFloatIsDecidedInDoubleByEveryKernel) {
  // A ray along z through the line of edge BC, off it by 2^-46 in the edge function: in
  // float, U = cx by - cy bx rounds to exactly 0 and the ray would count as on the edge (a
  // hit); in double, U = -2^-46 has the other sign than V and W, and the ray misses. The
  // paper's fallback decides such lanes in double; every kernel must (the one-triangle
  // test, the four-triangle block of every ISA, the packet forms triangle by triangle and
  // by (ray, triangle) pairs), from above and from below. Three triangles far away fill the
  // block, so that a packet of four rays takes the pairs form.
  const float e = 0x1p-23f;
  const vec4 a(-1.0f, 1.0f, 1.0f), b(1.0f, 1.0f + e, 1.0f), c(-(1.0f + e), -(1.0f + 2 * e), 1.0f);
  volatile float cx = c[0], cy = c[1], bx = b[0], by = b[1];  // the float products, unfolded
  ASSERT_EQ(cx * by - cy * bx, 0.0f);
  ASSERT_LT(double(c[0]) * b[1] - double(c[1]) * b[0], 0.0);
  Mesh m;
  m.positions = {a, b, c};
  m.faces = {{0, 1, 2}};
  for (int k = 1; k <= 3; ++k) {
    const float x = 100.0f * k;
    const auto first = static_cast<std::uint32_t>(m.positions.size());
    m.positions.insert(m.positions.end(), {vec4(x, 0, 1), vec4(x + 1, 0, 1), vec4(x, 1, 1)});
    m.faces.push_back({first, first + 1, first + 2});
  }
  m.face_materials.assign(m.faces.size(), 0);
  const Scene scene = test::geometry_scene({m});
  for (const Ray& ray : {Ray(vec4(0, 0, 0), vec4(0, 0, 1)), Ray(vec4(0, 0, 2), vec4(0, 0, -1))}) {
    float t, u, v;
    EXPECT_FALSE(intersect_watertight(Triangle::make(a, b, c), WatertightRay(ray), 0.0f, kInfinity,
                                      t, u, v));
    for (Isa isa : test::runnable_isas()) {
      const Accel acc = Accel::build(scene, BvhConfig{}, isa);
      EXPECT_FALSE(trace_closest(acc, ray, kInfinity, kTight).found()) << isa_name(isa);
      EXPECT_FALSE(trace_occluded(acc, ray, kInfinity, kTight)) << isa_name(isa);
      for (std::uint32_t n : {4u, 16u}) {  // pairs, then triangle by triangle
        const std::vector<Ray> rays(n, ray);
        const std::vector<float> t_max(n, kInfinity);
        const std::uint32_t begin[2] = {0, n};
        std::vector<Hit> hits(n);
        std::vector<std::uint8_t> occluded(n, 7);
        trace_closest_packets(acc, kTight, rays.data(), t_max.data(), begin, 1, hits.data());
        trace_occluded_packets(acc, kTight, rays.data(), t_max.data(), begin, 1, occluded.data());
        for (std::uint32_t l = 0; l < n; ++l) {
          EXPECT_FALSE(hits[l].found()) << isa_name(isa) << " packet of " << n << ", ray " << l;
          EXPECT_EQ(occluded[l], 0) << isa_name(isa) << " packet of " << n << ", ray " << l;
        }
      }
    }
  }
}

// --- spheres at the extremes ------------------------------------------------------------
// Squared distance, in double, from the sphere's centre to the line of the float ray:
// |oc x d|^2 / |d|^2, which does not cancel the way |oc|^2 - (oc·d)^2 would.
double line_distance2(const Sphere& s, const Ray& r) {
  double oc[3], d[3];
  for (int i = 0; i < 3; ++i) {
    oc[i] = double(s.center[i]) - r.org[i];
    d[i] = r.dir[i];
  }
  const double cx = oc[1] * d[2] - oc[2] * d[1], cy = oc[2] * d[0] - oc[0] * d[2],
               cz = oc[0] * d[1] - oc[1] * d[0];
  return (cx * cx + cy * cy + cz * cz) / (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

// Rays from `eye` aimed at random points of the sphere's visible disk. A float direction
// resolves ~6e-8 radians, so far away not every aimed ray really passes through a tiny
// sphere: the property is that every ray whose line passes within 0.999 r of the centre
// (decided in double) is hit. Returns (rays that pass through, of those the misses).
std::pair<std::size_t, std::size_t> sphere_misses(const Sphere& s, const vec4& eye, int n,
                                                  unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const vec4 axis = normalize(s.center - eye);
  const vec4 side = normalize(cross(axis, std::fabs(axis[1]) < 0.9f ? vec4(0, 1, 0) : vec4(1, 0, 0)));
  const vec4 up = cross(side, axis);
  std::size_t through = 0, misses = 0;
  for (int i = 0; i < n; ++i) {
    const float a = u(rng), b = u(rng);
    const Ray r(eye, normalize(s.center + (side * a + up * b) * s.radius - eye));
    if (line_distance2(s, r) > 0.998 * double(s.radius) * s.radius) continue;
    ++through;
    float t;
    misses += !intersect(s, r, 0.0f, kInfinity, t);
  }
  return {through, misses};
}

TEST(SphereExtremes, TinySphereFarAwayLosesNoHits) {
  for (const vec4& c : {vec4(0, 0, -1e4f), vec4(3e3f, -2e3f, -1e4f), vec4(-7e3f, 7e3f, 1e3f)}) {
    const auto [through, misses] = sphere_misses(Sphere{c, 1e-4f}, vec4(0, 0, 0), 100000, 1);
    EXPECT_GT(through, 100u) << c[0];  // enough rays really pass through it
    EXPECT_EQ(misses, 0u) << c[0];
  }
}

TEST(SphereExtremes, HugeSphereNearTheOriginLosesNoHits) {
  const Sphere s{vec4(0, 0, 0), 1e6f};
  const auto [through, misses] = sphere_misses(s, vec4(0, 0, 3e6f), 100000, 3);
  EXPECT_GT(through, 50000u);
  EXPECT_EQ(misses, 0u);
  // From inside, every direction hits at distance ~1e6.
  std::mt19937 rng(4);
  for (int i = 0; i < 10000; ++i) {
    float t;
    ASSERT_TRUE(intersect(s, Ray(vec4(0, 0, 0), test::random_direction(rng)), 0, kInfinity, t));
    ASSERT_NEAR(t, 1e6f, 1e6f * 1e-6f);
  }
}

// The far root of |o + t d - c| = r in double precision: the oracle for the float test.
double far_root(const Sphere& s, const Ray& r) {
  double oc[3], d[3], b = 0, cc = 0;
  for (int i = 0; i < 3; ++i) {
    oc[i] = double(r.org[i]) - s.center[i];
    d[i] = r.dir[i];
    b += oc[i] * d[i];
    cc += oc[i] * oc[i];
  }
  const double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  const double disc = b * b - dd * (cc - double(s.radius) * s.radius);
  return (-b + std::sqrt(std::max(disc, 0.0))) / dd;
}

TEST(SphereExtremes, RaysLeavingFromTheSurfaceDoNotHitItAgainAndInwardOnesCrossIt) {
  for (float r : {1e-3f, 1.0f, 1e3f, 1e5f}) {
    const Sphere s{vec4(0.3f, -0.2f, 0.1f) * r, r};
    std::mt19937 rng(5);
    for (int i = 0; i < 2000; ++i) {
      const vec4 n = test::random_direction(rng);
      const vec4 p = s.center + n * s.radius;  // on the surface, as the tracer re-projects
      vec4 out = test::random_direction(rng);
      if (float(dot(out, n)) < 0.0f) out = -out;
      float t;
      EXPECT_FALSE(intersect(s, Ray(offset_ray_origin(p, n, 2 * r), out), 0.0f, kInfinity, t))
          << "self-hit at r=" << r << " t=" << t;
      // Inward: the far side, never the entry point.
      const vec4 in = normalize(-n + 0.5f * test::random_direction(rng));
      if (float(dot(in, n)) >= -0.05f) continue;
      const Ray inward(offset_ray_origin(p, -n, 2 * r), in);
      ASSERT_TRUE(intersect(s, inward, 0.0f, kInfinity, t)) << r;
      EXPECT_NEAR(t, far_root(s, inward), 1e-5 * r) << r;
    }
  }
}

// --- degenerate rays ---------------------------------------------------------------------
TEST(DegenerateRays, ZeroOrNaNDirectionsAndNaNOriginsHitNothingAndDoNotCrash) {
  Scene scene = test::geometry_scene({test::random_soup(200, 0.3f, 51)},
                                     {Sphere{vec4(0, 0, 0), 0.5f}});
  scene.planes.push_back(Plane{vec4(0, 1, 0), 1.0f});
  scene.plane_materials.push_back(0);
  const Accel acc = Accel::build(scene, BvhConfig{});
  const float nan = std::nanf("");
  const std::vector<Ray> rays = {Ray(vec4(0, 0, 3), vec4(0, 0, 0)), Ray(vec4(0, 0, 3), vec4(nan, 0, -1)),
                                 Ray(vec4(nan, 0, 3), vec4(0, 0, -1)),
                                 Ray(vec4(0, 0, 3), vec4(kInfinity, 0, 0))};
  for (Isa isa : test::runnable_isas()) {
    const Accel a = Accel::build(scene, BvhConfig{}, isa);
    for (const Ray& r : rays)
      for (TraceOptions o : {kFast, kTight}) {
        EXPECT_FALSE(trace_closest(a, r, kInfinity, o).found()) << isa_name(isa);
        EXPECT_FALSE(trace_occluded(a, r, 10.0f, o)) << isa_name(isa);
      }
  }
}

}  // namespace
}  // namespace rt2
