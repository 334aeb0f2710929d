// The wide BVH on real meshes: 10^5 random rays per mesh (release; 10^4 under sanitizers),
// for every instruction set and both triangle tests, with and without the prefetches of a
// large tree (WideBvh::prefetch_pushed), counting the nodes and blocks visited or not (the
// walks compiled with and without counters, rt2/kernel/wide_traverse.h), give exactly the
// closest hit of a reference kernel — the binary SAH tree walked one triangle at a time with
// the one-triangle tests of rt2/geometry/triangle.h (itself checked against brute force over every
// triangle on random soups, bvh_test.cpp); the any-hit walk finds a hit exactly where that
// kernel does. Meshes: those of scripts/fetch-meshes that are present (scripts/test fetches
// the bunny); a missing one is skipped with its name.
#include <gtest/gtest.h>

#include <filesystem>

#include "rt2/bvh/traverse.h"
#include "rt2/io/scene_io.h"
#include "rt2/render/trace.h"
#include "tests/rt2/test_util.h"

namespace rt2 {
namespace {

using test::kSampleScale;

// The reference kernel: the binary tree over acc.tris, leaves tested triangle by triangle in
// index order (ties to the smaller index, as the wide walk does).
class BinaryOracle {
 public:
  explicit BinaryOracle(const Accel& acc) : acc_(acc) {
    std::vector<Aabb> boxes;
    for (const Triangle& t : acc.tris) {
      Aabb b;
      b.grow(t.v0), b.grow(t.v1), b.grow(t.v2);
      boxes.push_back(b);
    }
    bvh_ = build_bvh(boxes, BvhConfig{4, Split::sah, 16, 1});
  }

  Hit closest(const Ray& r, bool watertight) const {
    Hit h;
    const RayPre pre(r);
    const WatertightRay shear(r);
    float t_max = kInfinity;
    traverse<false>(bvh_, pre, 0.0f, t_max, [&](std::uint32_t first, std::uint32_t count, float& tm) {
      for (std::uint32_t i = first; i < first + count; ++i) {
        const std::uint32_t k = bvh_.order[i];
        float t, u, v;
        // Inclusive bound so that a tie with the best so far is seen and decided by index.
        const float bound = std::nextafter(h.t, kInfinity);
        const bool hit = watertight ? intersect_watertight(acc_.tris[k], shear, 0.0f, bound, t, u, v)
                                    : intersect(acc_.tris[k], r, 0.0f, bound, t, u, v);
        if (hit && (t < h.t || (t == h.t && k < h.prim))) {
          h.t = t, h.u = u, h.v = v, h.prim = k;
          tm = t;
        }
      }
      return false;
    });
    return h;
  }

 private:
  const Accel& acc_;
  Bvh bvh_;
};

class RealMesh : public ::testing::TestWithParam<const char*> {};

TEST_P(RealMesh, EveryIsaTriangleTestPrefetchAndCountingFindsThePreviousKernelsHitOnRandomRays) {
  const std::string path = std::string(RT2_SOURCE_DIR) + "/data/meshes/" + GetParam() + ".obj";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is not fetched (scripts/fetch-meshes)";
  Scene scene = frame_obj(path);
  scene.planes.clear();
  scene.plane_materials.clear();
  const Accel first = Accel::build(scene, BvhConfig{});
  const BinaryOracle oracle(first);
  const auto rays = test::random_rays(first, 100'000 / kSampleScale, 77, 1.5f * scene.size());
  std::vector<Hit> expected[2];
  for (bool watertight : {false, true}) {
    expected[watertight].resize(rays.size());
#pragma omp parallel for schedule(dynamic, 512)
    for (std::size_t i = 0; i < rays.size(); ++i) expected[watertight][i] = oracle.closest(rays[i], watertight);
  }
  for (Isa isa : test::runnable_isas()) {
    Accel acc = Accel::build(scene, BvhConfig{}, isa);
    ASSERT_EQ(acc.tris.size(), first.tris.size());
    // These trees are below kPrefetchPushedBytes.
    EXPECT_FALSE(acc.bvh8.prefetch_pushed || acc.bvh16.prefetch_pushed);
    for (int run = 0; run < 8; ++run) {
      const bool watertight = run & 1, prefetch = run & 2, counted = run & 4;
      acc.bvh8.prefetch_pushed = acc.bvh16.prefetch_pushed = prefetch;
      std::vector<Hit> hits(rays.size());
      const std::vector<float> t_max(rays.size(), kInfinity);
      TraversalCounts counts;
      trace_closest(acc, {watertight}, rays.data(), t_max.data(), rays.size(), hits.data(),
                    counted ? &counts : nullptr);
      std::vector<std::uint8_t> occluded(rays.size());
      trace_occluded(acc, {watertight}, rays.data(), t_max.data(), rays.size(), occluded.data(),
                     counted ? &counts : nullptr);
      if (counted) {
        EXPECT_GE(counts.nodes, 2 * rays.size()) << isa_name(isa);  // roots, at least
      }
      std::size_t found = 0, differ = 0, occlusion_differs = 0;
      for (std::size_t i = 0; i < rays.size(); ++i) {
        const Hit& e = expected[watertight][i];
        found += e.found();
        // Both trees come from the same scene: triangles in its face order, so the same
        // index means the same triangle.
        differ += !(hits[i].t == (e.found() ? e.t : kInfinity) && hits[i].prim == e.prim &&
                    (!e.found() || (hits[i].u == e.u && hits[i].v == e.v)));
        occlusion_differs += occluded[i] != (e.found() ? 1 : 0);
      }
      EXPECT_EQ(differ, 0u) << isa_name(isa) << (watertight ? " watertight" : " fast")
                            << (prefetch ? ", every pushed child prefetched" : "")
                            << (counted ? ", counted" : "");
      EXPECT_EQ(occlusion_differs, 0u) << isa_name(isa) << (watertight ? " watertight" : " fast")
                                       << (counted ? ", counted" : "") << ": any hit";
      EXPECT_GT(found, rays.size() / 3);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(FetchedMeshes, RealMesh,
                         ::testing::Values("bunny00", "ChineseDragon-10kv", "armadillo",
                                           "refined_elephant"));

}  // namespace
}  // namespace rt2
