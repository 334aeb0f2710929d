// tests/rt2/bvh/instance_test.cpp — the two-level tree (rt2/bvh/accel.h, rt2/kernel/instances.h)
// against its oracles: an identity instance is the flattened mesh bit for bit; moved,
// turned, scaled and mirrored instances answer as brute force over their triangles placed in
// the world in double precision; packets equal single rays; a rebuilt top level equals a
// fresh build.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "rt2/image/image_compare.h"
#include "rt2/render/trace.h"
#include "rt2/scene/builtin_scene.h"
#include "tests/rt2/test_util.h"

namespace rt2 {
namespace {

// A random rotation, non-uniform scale (mirrored when `mirror`) and translation.
Affine random_affine(std::mt19937& rng, bool mirror) {
  std::uniform_real_distribution<float> angle(-180.0f, 180.0f), scale(0.3f, 2.5f),
      shift(-6.0f, 6.0f);
  Transform xf;
  xf.rotate_degrees = vec4(angle(rng), angle(rng), angle(rng));
  xf.scale = vec4(scale(rng), scale(rng), scale(rng));
  if (mirror) xf.scale = vec4(-xf.scale[0], xf.scale[1], xf.scale[2]);
  xf.translate = vec4(shift(rng), shift(rng), shift(rng));
  return affine_of(xf);
}

// `m` placed in the world by `a`, in double, rounded once, its normals by the inverse
// transpose; a mirroring transform turns the winding back (as apply_transform does).
Mesh placed(const Mesh& m, const Affine& a) {
  Mesh out = m;
  for (vec4& p : out.positions) {
    const auto q = a.point({p[0], p[1], p[2]});
    p = vec4(float(q[0]), float(q[1]), float(q[2]));
  }
  const Affine inv = a.inverse();
  for (vec4& n : out.normals) {
    double q[3], len = 0.0;
    for (int r = 0; r < 3; ++r) {
      q[r] = inv.m[0][r] * n[0] + inv.m[1][r] * n[1] + inv.m[2][r] * n[2];
      len += q[r] * q[r];
    }
    len = std::sqrt(len);
    n = vec4(float(q[0] / len), float(q[1] / len), float(q[2] / len));
  }
  if (a.determinant() < 0)
    for (auto& f : out.faces) std::swap(f[1], f[2]);
  return out;
}

// A soup instanced `count` times (every third one mirrored), and the same triangles
// flattened into the world.
struct Pair {
  Scene instanced, flattened;
};
Pair instanced_soups(int count, unsigned seed, unsigned mesh_seed = 1, std::size_t soup_size = 400) {
  Pair p;
  p.instanced = test::geometry_scene({});
  p.flattened = test::geometry_scene({});
  const Mesh soup = test::random_soup(soup_size, 0.3f, mesh_seed);
  p.instanced.instanced_meshes.push_back(soup);
  std::mt19937 rng(seed);
  for (int i = 0; i < count; ++i) {
    Instance in;
    in.to_world = random_affine(rng, i % 3 == 2);
    p.instanced.instances.push_back(in);
    p.flattened.meshes.push_back(placed(soup, in.to_world));
  }
  return p;
}

TEST(Instances, AnIdentityInstanceAnswersAsTheFlattenedMeshBitForBit) {
  const Mesh soup = test::random_soup(2000, 0.2f, 11);
  Scene flat = test::geometry_scene({soup});
  Scene inst = test::geometry_scene({});
  inst.instanced_meshes.push_back(soup);
  inst.instances.push_back(Instance{});
  for (Isa isa : test::runnable_isas()) {
    const Accel a = Accel::build(flat, BvhConfig{}, isa), b = Accel::build(inst, BvhConfig{}, isa);
    const std::vector<Ray> rays = test::random_rays(a, 4000 / test::kSampleScale, 5);
    for (bool watertight : {false, true}) {
      const TraceOptions opt{watertight};
      for (std::size_t i = 0; i < rays.size(); ++i) {
        const Hit ha = trace_closest(a, rays[i], kInfinity, opt);
        Hit hb = trace_closest(b, rays[i], kInfinity, opt);
        ASSERT_EQ(hb.instance, hb.found() ? 0u : kNoInstance) << i;
        hb.instance = kNoInstance;
        ASSERT_TRUE(test::bitwise_same(ha, hb)) << isa_name(isa) << " ray " << i;
        const float t_max = ha.found() ? ha.t * 1.5f : 10.0f;
        ASSERT_EQ(trace_occluded(a, rays[i], t_max, opt), trace_occluded(b, rays[i], t_max, opt));
      }
    }
  }
}

TEST(Instances, TheBuiltInSceneWithItsChairInstancedRendersTheSameBits) {
  const Scene flat = make_default_scene();
  Scene inst = flat;
  inst.instanced_meshes = inst.meshes;
  inst.meshes.clear();
  inst.instances.push_back(Instance{});
  RenderSettings st;
  st.width = 96;
  st.height = 72;
  st.depth = 6;
  for (Isa isa : test::runnable_isas()) {
    const Image a = test::render_scene(flat, st, {Backend::serial, 1, 1}, {}, isa);
    const Image b = test::render_scene(inst, st, {Backend::omp, 2, 1}, {}, isa);
    ASSERT_EQ(a.rgb, b.rgb) << isa_name(isa);
  }
}

// The closest hit's distance against brute force over the placed triangles: the same rays
// hit (but for a few grazing an edge, which rounding may decide either way) at the same
// distance to a few ulps of the transforms.
TEST(Instances, MovedTurnedScaledAndMirroredInstancesHitWhereBruteForceDoes) {
  const Pair p = instanced_soups(20, 3, 3);
  for (Isa isa : test::runnable_isas()) {
    const Accel inst = Accel::build(p.instanced, BvhConfig{}, isa);
    const Accel flat = Accel::build(p.flattened, BvhConfig{}, isa);
    const std::vector<Ray> rays = test::random_rays(flat, 3000 / test::kSampleScale, 9, 8.0f);
    for (bool watertight : {false, true}) {
      std::size_t disagree = 0, hits = 0;
      for (const Ray& r : rays) {
        const Hit h = trace_closest(inst, r, kInfinity, TraceOptions{watertight});
        const Hit o = test::brute_force(flat, r, 0.0f, kInfinity, watertight);
        if (h.found() != o.found()) {
          ++disagree;
          continue;
        }
        if (!h.found()) continue;
        ++hits;
        ASSERT_LT(h.instance, inst.instances.size());
        if (std::fabs(h.t - o.t) > 1e-4f * (1.0f + o.t)) ++disagree;
      }
      EXPECT_GT(hits, rays.size() / 3);
      EXPECT_LE(disagree, rays.size() / 500) << isa_name(isa) << " watertight " << watertight;
    }
  }
}

TEST(Instances, AnyHitAgreesWithTheClosestHitInEveryInstance) {
  const Pair p = instanced_soups(30, 4);
  const Accel acc = Accel::build(p.instanced, BvhConfig{});
  const std::vector<Ray> rays = test::random_rays(
      Accel::build(p.flattened, BvhConfig{}), 4000 / test::kSampleScale, 2, 8.0f);
  for (const Ray& r : rays) {
    const Hit h = trace_closest(acc, r);
    if (!h.found()) {
      EXPECT_FALSE(trace_occluded(acc, r, kInfinity));
      continue;
    }
    EXPECT_TRUE(trace_occluded(acc, r, h.t * 1.0001f));
    EXPECT_FALSE(trace_occluded(acc, r, h.t * 0.9999f));
  }
}

// Packets walk the instances' trees as packets too; ties between coincident instances (a
// duplicated node) go to the smaller instance either way.
TEST(Instances, PacketsThroughInstancesEqualSingleRaysBitForBit) {
  Pair p = instanced_soups(25, 5);
  p.instanced.meshes.push_back(test::random_soup(300, 0.3f, 8));  // and world triangles
  Material glass;
  glass.transparency = 0.5f;
  Instance twin = p.instanced.instances[0];
  twin.material = p.instanced.add_material("glass", glass);
  p.instanced.instances.push_back(twin);
  for (Isa isa : test::runnable_isas()) {
    const Accel acc = Accel::build(p.instanced, BvhConfig{}, isa);
    std::vector<Ray> rays;
    std::vector<float> t_max;
    std::vector<std::uint32_t> begin{0};
    const vec4 eye(0.0f, 1.0f, -14.0f);
    for (int ty = 0; ty < 64; ty += 4)
      for (int tx = 0; tx < 64; tx += 4) {
        for (int y = ty; y < ty + 4; ++y)
          for (int x = tx; x < tx + 4; ++x) {
            const vec4 target((x - 32) * 0.25f, (32 - y) * 0.25f, 0.0f);
            rays.emplace_back(eye, normalize(target - eye));
            t_max.push_back((x + y) % 7 == 0 ? 12.0f : kInfinity);
          }
        begin.push_back(std::uint32_t(rays.size()));
      }
    const std::size_t n = rays.size(), packets = begin.size() - 1;
    const std::uint32_t twins[2] = {0, 25};
    for (bool watertight : {false, true}) {
      const TraceOptions opt{watertight};
      std::vector<Hit> single(n), packed(n);
      std::vector<std::uint8_t> occ(n), occ_packed(n);
      std::vector<float> passed(n), passed_packed(n);
      TraversalCounts counts;
      trace_closest(acc, opt, rays.data(), t_max.data(), n, single.data());
      trace_closest_packets(acc, opt, rays.data(), t_max.data(), begin.data(), packets,
                            packed.data(), &counts);
      trace_occluded(acc, opt, rays.data(), t_max.data(), n, occ.data());
      trace_occluded_packets(acc, opt, rays.data(), t_max.data(), begin.data(), packets,
                             occ_packed.data(), &counts);
      trace_transmittance(acc, p.instanced.materials, opt, rays.data(), t_max.data(), n,
                          passed.data());
      trace_transmittance_packets(acc, p.instanced.materials, opt, rays.data(), t_max.data(),
                                  begin.data(), packets, passed_packed.data());
      std::size_t in_instances = 0, in_twins = 0;
      for (std::size_t i = 0; i < n; ++i) {
        ASSERT_TRUE(test::bitwise_same(single[i], packed[i])) << isa_name(isa) << " ray " << i;
        ASSERT_EQ(occ[i], occ_packed[i]) << isa_name(isa) << " ray " << i;
        ASSERT_EQ(passed[i], passed_packed[i]) << isa_name(isa) << " ray " << i;
        in_instances += single[i].instance != kNoInstance;
        if (single[i].instance == twins[0] || single[i].instance == twins[1]) {
          EXPECT_EQ(single[i].instance, std::min(twins[0], twins[1])) << "ties: the smaller";
          ++in_twins;
        }
      }
      EXPECT_GT(in_instances, n / 20);
      EXPECT_GT(in_twins, 0u);
      EXPECT_GT(counts.packet_rays, n / 4);  // the instances' trees walked as packets
    }
  }
}

TEST(Instances, ARebuiltTopLevelAnswersAsAFreshBuildBitForBit) {
  Pair before = instanced_soups(50, 6), after = instanced_soups(50, 7);
  Accel moved = Accel::build(before.instanced, BvhConfig{});
  moved.place_instances(after.instanced.instances, 2);
  const Accel fresh = Accel::build(after.instanced, BvhConfig{});
  const std::vector<Ray> rays =
      test::random_rays(Accel::build(after.flattened, BvhConfig{}), 3000 / test::kSampleScale, 1,
                        8.0f);
  for (std::size_t i = 0; i < rays.size(); ++i)
    ASSERT_TRUE(test::bitwise_same(trace_closest(moved, rays[i]), trace_closest(fresh, rays[i])))
        << i;
}

// Past Accel::kSahInstances the top level is a linear BVH: single rays and packets through
// it still hit where the flattened copies' tree does, and packets as single rays.
TEST(Instances, BothTopLevelBuildsHitWhereTheFlattenedCopiesDo) {
  for (const int count : {int(Accel::kSahInstances) / 8, int(Accel::kSahInstances) + 300}) {
    const Pair p = instanced_soups(count, 8, 2, 6);
    const Accel inst = Accel::build(p.instanced, BvhConfig{});
    const Accel flat = Accel::build(p.flattened, BvhConfig{});
    std::vector<Ray> rays = test::random_rays(flat, 4096 / test::kSampleScale, 3, 8.0f);
    rays.resize(rays.size() / 16 * 16);
    std::vector<float> t_max(rays.size(), kInfinity);
    std::vector<std::uint32_t> begin;
    for (std::uint32_t i = 0; i <= rays.size(); i += 16) begin.push_back(i);
    std::vector<Hit> single(rays.size()), packed(rays.size());
    trace_closest(inst, {}, rays.data(), t_max.data(), rays.size(), single.data());
    trace_closest_packets(inst, {}, rays.data(), t_max.data(), begin.data(), begin.size() - 1,
                          packed.data(), nullptr);
    std::size_t hits = 0, disagree = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
      ASSERT_TRUE(test::bitwise_same(single[i], packed[i])) << count << " ray " << i;
      const Hit o = trace_closest(flat, rays[i]);
      hits += o.found();
      if (single[i].found() != o.found() ||
          (o.found() && std::fabs(single[i].t - o.t) > 1e-4f * (1.0f + o.t)))
        ++disagree;
    }
    EXPECT_GT(hits, rays.size() / 3) << count;
    // the copies are rounded once, the instanced rays transformed: a ray grazing an edge
    // may go either way
    EXPECT_LE(disagree, rays.size() / 500 + 1) << count;
  }
}

TEST(Instances, TheInstanceMaterialReplacesTheMeshMaterials) {
  Scene s = test::geometry_scene({});
  Material red;
  red.diffuse = vec4(1.0f, 0.0f, 0.0f);
  const std::uint32_t r = s.add_material("red", red);
  s.instanced_meshes.push_back(test::random_soup(200, 0.4f, 3));
  Instance plain, painted;
  painted.material = r;
  painted.to_world.m[0][3] = 5.0;
  s.instances = {plain, painted};
  const Accel acc = Accel::build(s, BvhConfig{});
  const Mesh& m = s.instanced_meshes[0];
  const vec4 centroid =
      (m.positions[m.faces[0][0]] + m.positions[m.faces[0][1]] + m.positions[m.faces[0][2]]) *
      (1.0f / 3.0f);
  for (std::uint32_t i = 0; i < acc.instances.size(); ++i) {
    const vec4 target = acc.instances[i].to_world.point(centroid);
    const Hit h = trace_closest(acc, Ray(target - vec4(0.0f, 0.0f, 5.0f), vec4(0.0f, 0.0f, 1.0f)));
    ASSERT_TRUE(h.found());
    EXPECT_EQ(h.instance, i);
    EXPECT_EQ(acc.material_of(h.prim, h.instance), i == 1 ? r : 0u);
  }
}

// The image of instances against the image of their triangles placed in the world: the
// same picture (normals, shading, shadows, reflections) to the rounding of the transforms.
TEST(Instances, InstancedMeshesRenderAsTheirFlattenedCopies) {
  Scene inst = make_default_scene(), flat = make_default_scene();
  const Mesh chair = inst.meshes.front();
  inst.meshes.clear();
  flat.meshes.clear();
  inst.instanced_meshes.push_back(chair);
  std::mt19937 rng(17);
  for (int i = 0; i < 4; ++i) {
    Transform xf;
    xf.translate = vec4(-0.9f + 0.6f * float(i), 0.0f, 0.3f * float(i % 2));
    xf.rotate_degrees = vec4(0.0f, 40.0f * float(i), 0.0f);
    xf.scale = vec4(i == 3 ? -0.5f : 0.5f, 0.5f, 0.5f);
    Instance in;
    in.to_world = affine_of(xf);
    inst.instances.push_back(in);
    flat.meshes.push_back(placed(chair, in.to_world));
  }
  RenderSettings st;
  st.width = 160;
  st.height = 120;
  st.depth = 6;
  const Image a = test::render_scene(inst, st), b = test::render_scene(flat, st);
  const ImageError e = compare_images(a, b);
  EXPECT_GT(e.psnr, 40.0);
  EXPECT_GT(e.ssim, 0.99);
}

}  // namespace
}  // namespace rt2
