// tests/rt2/bvh/refit_test.cpp — refitting trees to moved triangles (refit_bvh, Accel::refit)
// against their oracles: a refit to unmoved triangles is the built tree, byte for byte; a tree
// refit to a deformed mesh answers every ray (closest hit, any hit, single rays and packets)
// as a fresh build over the deformed mesh does and as brute force does, bit for bit; the
// cost growth Accel::refit reports is 1 when nothing moved and large when triangles scatter.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>
#include <vector>

#include "rt2/io/scene_io.h"
#include "rt2/render/trace.h"
#include "tests/rt2/test_util.h"

namespace rt2 {
namespace {

// `m` bent: a twist about y growing with height, a wave along x, and `jitter` of noise per
// vertex (shared vertices stay shared: each vertex moves once).
Mesh deformed(const Mesh& m, float twist, float jitter, unsigned seed) {
  Mesh out = m;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> noise(-jitter, jitter);
  for (vec4& p : out.positions) {
    const float a = twist * p[1], c = std::cos(a), s = std::sin(a);
    const float x = c * p[0] - s * p[2], z = s * p[0] + c * p[2];
    p = vec4(x + noise(rng), p[1] + 0.2f * std::sin(3.0f * x) + noise(rng), z + noise(rng));
  }
  return out;
}

// Whether two arrays of n elements hold the same bytes (an empty one's data may be null).
template <class T>
bool same_bytes(const T* a, const T* b, std::size_t n) {
  return n == 0 || std::memcmp(a, b, n * sizeof(T)) == 0;
}

template <int N>
bool same_tree(const WideBvh<N>& a, const WideBvh<N>& b) {
  return a.root == b.root && a.quantized == b.quantized && a.nodes.size() == b.nodes.size() &&
         a.quantized_nodes.size() == b.quantized_nodes.size() &&
         same_bytes(a.nodes.data(), b.nodes.data(), a.nodes.size()) &&
         same_bytes(a.quantized_nodes.data(), b.quantized_nodes.data(), a.quantized_nodes.size()) &&
         std::memcmp(&a.bounds, &b.bounds, sizeof(Aabb)) == 0;
}

bool same_blocks(const TriangleBlocks& a, const TriangleBlocks& b) {
  return a.size() == b.size() && same_bytes(a.data(), b.data(), a.size());
}

TEST(Refit, ARefitToUnmovedTrianglesIsTheBuiltTreeByteForByte) {
  const Scene scene = test::geometry_scene({test::random_soup(3000, 0.3f, 5)});
  for (Isa isa : test::runnable_isas())
    for (int threads : {1, 2})
      for (NodeLayout layout : {NodeLayout::plain, NodeLayout::quantized}) {
        BvhConfig config;
        config.nodes = layout;
        Accel acc = Accel::build(scene, config, isa);
        with_bvh_width(isa, [&](auto width) {
          constexpr int N = decltype(width)::value;
          const WideBvh<N> built = acc.wide<N>();
          const TriangleBlocks blocks = acc.blocks;
          refit_bvh<N>(acc.wide<N>(), acc.tris, acc.blocks, threads);
          EXPECT_TRUE(same_tree(built, acc.wide<N>())) << isa_name(isa) << ", " << threads;
          EXPECT_TRUE(same_blocks(blocks, acc.blocks)) << isa_name(isa) << ", " << threads;
        });
      }
}

// Every ray's closest hit and any hit through `refit` equal `fresh`'s and brute force's, bit
// for bit, single rays and packets (brute force on every `brute_every`-th ray; 0: none, for
// instances, which brute force over acc.tris does not place); returns the rays that hit.
std::size_t expect_refit_answers_as_fresh(const Accel& refit, const Accel& fresh,
                                          const std::vector<Ray>& rays, const char* what,
                                          std::size_t brute_every) {
  std::size_t hits = 0;
  const std::vector<float> t_max(rays.size(), kInfinity);
  std::vector<std::uint32_t> packet_begin;
  for (std::size_t i = 0; i <= rays.size(); i += 16) packet_begin.push_back(std::uint32_t(i));
  if (packet_begin.back() != rays.size()) packet_begin.push_back(std::uint32_t(rays.size()));
  for (bool watertight : {false, true}) {
    std::vector<Hit> a(rays.size()), b(rays.size()), p(rays.size());
    trace_closest(refit, {watertight}, rays.data(), t_max.data(), rays.size(), a.data());
    trace_closest(fresh, {watertight}, rays.data(), t_max.data(), rays.size(), b.data());
    trace_closest_packets(refit, {watertight}, rays.data(), t_max.data(), packet_begin.data(),
                          packet_begin.size() - 1, p.data());
    std::vector<std::uint8_t> oa(rays.size()), ob(rays.size());
    std::vector<float> segment(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i)
      segment[i] = b[i].found() ? b[i].t * (i % 2 ? 1.0001f : 0.9999f) : 100.0f;
    trace_occluded(refit, {watertight}, rays.data(), segment.data(), rays.size(), oa.data());
    trace_occluded(fresh, {watertight}, rays.data(), segment.data(), rays.size(), ob.data());
    std::size_t differ = 0, packets_differ = 0, brute_differs = 0, occlusion_differs = 0;
    hits = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
      hits += b[i].found();
      differ += !test::bitwise_same(a[i], b[i]);
      packets_differ += !test::bitwise_same(p[i], b[i]);
      occlusion_differs += oa[i] != ob[i];
      if (brute_every && i % brute_every == 0) {
        const Hit r = test::brute_force(fresh, rays[i], 0.0f, kInfinity, watertight);
        brute_differs += !(a[i].t == r.t && a[i].prim == r.prim &&
                           (!r.found() || (a[i].u == r.u && a[i].v == r.v)));
      }
    }
    const char* test_name = watertight ? " watertight" : " fast";
    EXPECT_EQ(differ, 0u) << what << test_name;
    EXPECT_EQ(packets_differ, 0u) << what << test_name << ", packets";
    EXPECT_EQ(brute_differs, 0u) << what << test_name << ", brute force";
    EXPECT_EQ(occlusion_differs, 0u) << what << test_name << ", any hit";
  }
  return hits;
}

TEST(Refit, RefitTreesAnswerEveryRayAsAFreshBuildAndBruteForceOnDeformedMeshes) {
  std::vector<std::pair<std::string, Mesh>> meshes = {{"soup", test::random_soup(2000, 0.3f, 9)}};
  const std::string bunny = std::string(RT2_SOURCE_DIR) + "/data/meshes/bunny00.obj";
  if (std::filesystem::exists(bunny)) meshes.push_back({"bunny", load_scene(bunny).meshes[0]});
  for (const auto& [name, mesh] : meshes)
    for (Isa isa : test::runnable_isas())
      for (NodeLayout layout : {NodeLayout::plain, NodeLayout::quantized}) {
        if (name != "soup" && layout == NodeLayout::quantized) continue;  // time
        BvhConfig config;
        config.nodes = layout;
        const std::size_t brute_every = mesh.faces.size() > 10000 ? 401 : 7;
        Accel acc = Accel::build(test::geometry_scene({mesh}), config, isa);
        // Deformed further and further, each refit from the one before (as frames are).
        for (int frame = 1; frame <= 3; ++frame) {
          const Scene moved = test::geometry_scene(
              {deformed(mesh, 0.6f * float(frame), 0.01f * float(frame), unsigned(frame))});
          ASSERT_TRUE(same_topology(test::geometry_scene({mesh}), moved));
          acc.refit(moved, config, 2);
          const Accel fresh = Accel::build(moved, config, isa);
          const std::vector<Ray> rays = test::random_rays(
              fresh, std::size_t(20000 / test::kSampleScale), 40u + unsigned(frame));
          const std::string what = name + ", " + isa_name(isa) + ", frame " +
                                   std::to_string(frame) +
                                   (layout == NodeLayout::quantized ? ", quantized" : "");
          EXPECT_GT(expect_refit_answers_as_fresh(acc, fresh, rays, what.c_str(), brute_every),
                    rays.size() / 4)
              << what;
        }
      }
}

TEST(Refit, RefitInstancedMeshesAnswerAsAFreshBuildOfTheMovedScene) {
  const Mesh mesh = test::random_soup(1500, 0.3f, 12);
  const auto scene_with = [](const Mesh& m, float shift) {
    Scene s = test::geometry_scene({test::random_soup(200, 0.3f, 13)});
    s.instanced_meshes = {m};
    for (int i = 0; i < 6; ++i) {
      Transform xf;
      xf.translate = vec4(float(i) - 3.0f + shift, 0.5f * float(i % 2), 0.0f);
      xf.rotate_degrees = vec4(15.0f * float(i), 0.0f, 0.0f);
      s.instances.push_back(Instance{0, affine_of(xf)});
    }
    return s;
  };
  for (Isa isa : test::runnable_isas()) {
    Accel acc = Accel::build(scene_with(mesh, 0.0f), BvhConfig{}, isa);
    const Scene moved = scene_with(deformed(mesh, 1.2f, 0.02f, 3), 0.25f);
    acc.refit(moved, BvhConfig{}, 1);
    const Accel fresh = Accel::build(moved, BvhConfig{}, isa);
    const std::vector<Ray> rays = test::random_rays(fresh, std::size_t(20000 / test::kSampleScale), 7);
    EXPECT_GT(expect_refit_answers_as_fresh(acc, fresh, rays, isa_name(isa), 0), rays.size() / 4);
  }
}

TEST(Refit, CostGrowthIsOneWhenNothingMovedAndLargeWhenTrianglesScatter) {
  const Mesh mesh = test::random_soup(4000, 0.05f, 21);
  Accel acc = Accel::build(test::geometry_scene({mesh}), BvhConfig{});
  EXPECT_EQ(acc.refit(test::geometry_scene({mesh}), BvhConfig{}), 1.0);
  Mesh scattered = mesh;  // every vertex to another's place: the tree's boxes span the scene
  std::mt19937 rng(3);
  std::shuffle(scattered.positions.begin(), scattered.positions.end(), rng);
  EXPECT_GT(acc.refit(test::geometry_scene({scattered}), BvhConfig{}), 4.0);
}

TEST(Refit, RefusesAndSameTopologyRejectsScenesWithOtherTriangles) {
  const Mesh mesh = test::random_soup(100, 0.3f, 2);
  Mesh fewer = mesh;
  fewer.faces.pop_back();
  fewer.face_materials.pop_back();
  Mesh turned = mesh;
  std::swap(turned.faces[0][1], turned.faces[0][2]);
  Mesh with_normals = mesh;
  with_normals.normals.assign(mesh.positions.size(), vec4(0.0f, 1.0f, 0.0f));
  const Scene a = test::geometry_scene({mesh});
  EXPECT_TRUE(same_topology(a, test::geometry_scene({deformed(mesh, 1.0f, 0.1f, 1)})));
  for (const Mesh& other : {fewer, turned, with_normals})
    EXPECT_FALSE(same_topology(a, test::geometry_scene({other})));
  EXPECT_FALSE(same_topology(a, test::geometry_scene({mesh, mesh})));
  Accel acc = Accel::build(a, BvhConfig{});
  EXPECT_THROW(acc.refit(test::geometry_scene({fewer}), BvhConfig{}), Error);
}

}  // namespace
}  // namespace rt2
