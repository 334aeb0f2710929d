// The batch queries of rt2/render/trace.h: trace_closest answers exactly as brute force,
// trace_occluded agrees with the closest hit's distance, sub-ranges give the
// same answers as one call, and accel_bytes counts at least the arrays a query reads.
#include "rt2/render/trace.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <string>
#include <vector>

#include "rt2/scene/shapes.h"
#include "tests/rt2/test_util.h"

namespace rt2 {
namespace {

// A closed mesh, a triangle soup, a sphere and a ground plane: every primitive kind.
Scene mixed_scene() {
  Scene s = test::geometry_scene(
      {make_icosphere(vec4(-0.4f, 0.1f, 0.0f), 0.5f, 2, 0), test::random_soup(200, 0.4f, 21)},
      {Sphere{vec4(0.5f, 0.3f, 0.2f), 0.3f}});
  s.planes.push_back(Plane{vec4(0.0f, 1.0f, 0.0f), 1.2f});  // y = -1.2
  s.plane_materials.push_back(0);
  return s;
}

// Half of the t_max are +inf, the others uniform in (0, 4).
std::vector<float> random_t_max(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> len(0.0f, 4.0f);
  std::vector<float> t(n);
  for (std::size_t i = 0; i < n; ++i) t[i] = i % 2 ? len(rng) : kInfinity;
  return t;
}

struct Fixture {
  Scene scene = mixed_scene();
  Accel acc = Accel::build(scene, BvhConfig{});
  std::vector<Ray> rays = test::random_rays(acc, 600, 5);
  std::vector<float> t_max = random_t_max(rays.size(), 6);
};

bool same(const Hit& a, const Hit& b) {
  return a.prim == b.prim && a.t == b.t && a.u == b.u && a.v == b.v;
}

TEST(Trace, ClosestEqualsBruteForceAndHitsEveryKind) {
  const Fixture f;
  std::size_t kinds[3] = {0, 0, 0};
  for (bool watertight : {false, true}) {
    std::vector<Hit> hits(f.rays.size());
    trace_closest(f.acc, TraceOptions{watertight}, f.rays.data(), f.t_max.data(), f.rays.size(),
                  hits.data());
    std::size_t mismatches = 0;
    for (std::size_t i = 0; i < f.rays.size(); ++i) {
      const Hit ref = test::brute_force(f.acc, f.rays[i], 0.0f, f.t_max[i], watertight);
      mismatches += !(hits[i].found() == ref.found() && hits[i].t == ref.t);
      if (hits[i].found()) ++kinds[prim_tag(hits[i].prim) >> 30];
    }
    EXPECT_EQ(mismatches, 0u) << "watertight=" << watertight;
  }
  EXPECT_GT(kinds[0], 0u) << "triangles";
  EXPECT_GT(kinds[1], 0u) << "spheres";
  EXPECT_GT(kinds[2], 0u) << "planes";
}

TEST(Trace, OccludedIsTheClosestHitBeforeTMax) {
  const Fixture f;
  const std::vector<float> unbounded(f.rays.size(), kInfinity);
  for (bool watertight : {false, true}) {
    const TraceOptions opt{watertight};
    std::vector<Hit> nearest(f.rays.size());
    trace_closest(f.acc, opt, f.rays.data(), unbounded.data(), f.rays.size(), nearest.data());
    std::vector<std::uint8_t> occluded(f.rays.size(), 7);
    trace_occluded(f.acc, opt, f.rays.data(), f.t_max.data(), f.rays.size(), occluded.data());
    std::size_t blocked = 0, open = 0, mismatches = 0;
    for (std::size_t i = 0; i < f.rays.size(); ++i) {
      const bool expected = nearest[i].t < f.t_max[i];
      mismatches += occluded[i] != (expected ? 1 : 0);
      blocked += expected;
      open += !expected;
    }
    EXPECT_EQ(mismatches, 0u) << "watertight=" << watertight;
    EXPECT_GT(blocked, f.rays.size() / 10);
    EXPECT_GT(open, f.rays.size() / 10);
  }
}

TEST(Trace, SubRangesAnswerAsOneCall) {
  const Fixture f;
  const std::size_t n = f.rays.size(), cut = n / 3;
  std::vector<Hit> whole(n), parts(n);
  std::vector<std::uint8_t> occ_whole(n), occ_parts(n);
  trace_closest(f.acc, {}, f.rays.data(), f.t_max.data(), n, whole.data());
  trace_closest(f.acc, {}, f.rays.data(), f.t_max.data(), cut, parts.data());
  trace_closest(f.acc, {}, f.rays.data() + cut, f.t_max.data() + cut, n - cut, parts.data() + cut);
  trace_occluded(f.acc, {}, f.rays.data(), f.t_max.data(), n, occ_whole.data());
  trace_occluded(f.acc, {}, f.rays.data(), f.t_max.data(), cut, occ_parts.data());
  trace_occluded(f.acc, {}, f.rays.data() + cut, f.t_max.data() + cut, n - cut,
                 occ_parts.data() + cut);
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_TRUE(same(whole[i], parts[i])) << i;
    EXPECT_EQ(occ_whole[i], occ_parts[i]) << i;
  }
}

TEST(Trace, ZeroOrNanTMaxHitsNothing) {
  const Fixture f;
  const std::size_t n = f.rays.size();
  for (float bound : {0.0f, std::numeric_limits<float>::quiet_NaN()}) {
    const std::vector<float> t_max(n, bound);
    std::vector<Hit> hits(n);
    std::vector<std::uint8_t> occluded(n, 7);
    trace_closest(f.acc, {}, f.rays.data(), t_max.data(), n, hits.data());
    trace_occluded(f.acc, {}, f.rays.data(), t_max.data(), n, occluded.data());
    std::size_t any = 0;
    for (std::size_t i = 0; i < n; ++i) any += hits[i].found() + occluded[i];
    EXPECT_EQ(any, 0u) << "t_max=" << bound;
  }
}

TEST(Trace, AccelBytesCountsTheTreesAndLeafBlocks) {
  const Fixture f;
  const std::size_t read = f.acc.bvh4.nodes.size() * sizeof(WideNode<4>) +
                           f.acc.bvh8.nodes.size() * sizeof(WideNode<8>) +
                           f.acc.bvh16.nodes.size() * sizeof(WideNode<16>) +
                           f.acc.blocks.size() * sizeof(TriangleBlock) +
                           f.acc.sphere_bvh.nodes.size() * sizeof(BvhNode);
  EXPECT_GE(accel_bytes(f.acc), read);
  EXPECT_LT(accel_bytes(f.acc), read + read / 4);  // the spheres' leaf order, nothing wild
  EXPECT_EQ(accel_bytes(Accel{}), 0u);
  // A block holds at most 4 triangles: at least 40 bytes per triangle.
  EXPECT_GE(f.acc.blocks.size() * sizeof(TriangleBlock), f.acc.tris.size() * 40);
}

// Accel::build finds each triangle's mesh by a search over the meshes' first triangles: every
// face of every mesh (an empty one between them, one of a single face after it) is in the
// Accel once, with its own material, and the hits name those triangles.
TEST(Trace, AccelHoldsEveryFaceOfEveryMeshOnceWithItsMaterial) {
  std::vector<Mesh> meshes = {make_icosphere(vec4(-0.4f, 0.1f, 0.0f), 0.5f, 2, 0), Mesh{},
                              test::random_soup(200, 0.4f, 21), Mesh{}};
  meshes[3].positions = {vec4(0, 0, 2), vec4(1, 0, 2), vec4(0, 1, 2)};
  meshes[3].faces = {{0, 1, 2}};
  Scene s = test::geometry_scene(meshes);
  for (std::uint32_t m = 1; m <= 3; ++m) s.add_material("m" + std::to_string(m), Material{});
  for (std::uint32_t m = 0; m < s.meshes.size(); ++m)
    s.meshes[m].face_materials.assign(s.meshes[m].faces.size(), m);
  using Key = std::array<float, 10>;  // three vertices, then the material
  const auto key = [](const Triangle& t, std::uint32_t material) {
    return Key{t.v0[0], t.v0[1], t.v0[2], t.v1[0], t.v1[1], t.v1[2],
               t.v2[0], t.v2[1], t.v2[2], float(material)};
  };
  std::vector<Key> want, got;
  for (const Mesh& m : s.meshes)
    for (std::size_t f = 0; f < m.faces.size(); ++f) {
      const auto& v = m.faces[f];
      want.push_back(key(Triangle::make(m.positions[v[0]], m.positions[v[1]], m.positions[v[2]]),
                         m.face_materials[f]));
    }
  const Accel acc = Accel::build(s, BvhConfig{});
  ASSERT_EQ(acc.tris.size(), want.size());
  ASSERT_EQ(acc.tri_materials.size(), want.size());
  for (std::size_t k = 0; k < acc.tris.size(); ++k) got.push_back(key(acc.tris[k], acc.tri_materials[k]));
  std::sort(want.begin(), want.end());
  std::sort(got.begin(), got.end());
  EXPECT_EQ(got, want);
  // The last mesh's one triangle, hit head on, is found with its material.
  const Ray down(vec4(0.25f, 0.25f, 5.0f), vec4(0.0f, 0.0f, -1.0f));
  const float t_max = kInfinity;
  Hit h;
  trace_closest(acc, TraceOptions{}, &down, &t_max, 1, &h);
  ASSERT_TRUE(h.found());
  EXPECT_EQ(h.t, 3.0f);
  EXPECT_EQ(acc.tri_materials[prim_index(h.prim)], 3u);
}

}  // namespace
}  // namespace rt2
