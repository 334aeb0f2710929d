// glTF animation (rt2/io/gltf_scene.cpp, rt2/scene/animation.h): a file posed at a time
// against the node tree evaluated by hand in long double (tests/rt2/io/animated_gltf.h), the
// lights and cameras of animated nodes, the choice of an animation, and the bounds on what
// a file's animations may make the loader read. Malformed animation data is in
// tests/hostile (gltf_anim_*). Each test names the property it checks.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "rt2/base/error.h"
#include "rt2/io/gltf_scene.h"
#include "rt2/io/scene_io.h"
#include "tests/rt2/io/animated_gltf.h"
#include "tests/rt2/temp_dir.h"

namespace rt2 {
namespace {

using Point = std::array<long double, 3>;

// "spin" by hand: node 0 turns about y by 90 degrees a second (0 ... 2 s) and steps along x
// (0, 1, 2 at 0, 1, 2 s); node 1 sits 0.5 above it, scaled by 1 + t^2 / 4 (0 ... 2 s).
Point spin_corner(const Point& p, double t) {
  const long double tc = std::clamp(t, 0.0, 2.0);
  const long double angle = tc * 3.14159265358979323846264338327950288L / 2;
  const long double step = t < 1 ? 0 : t < 2 ? 1 : 2;
  const long double s = 1 + tc * tc / 4;
  const Point q = {p[0] * s, p[1] * s + 0.5L, p[2] * s};
  // a turn about +y: x' = x cos + z sin, z' = -x sin + z cos
  return {step + q[0] * std::cos(angle) + q[2] * std::sin(angle), q[1],
          -q[0] * std::sin(angle) + q[2] * std::cos(angle)};
}

void expect_near(const vec4& got, const Point& want, const std::string& what) {
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(double(got[k]), double(want[std::size_t(k)]), 2e-6) << what << " axis " << k;
}

// The message of the rt2::Error loading `file` in `pose` throws ("" if it loads).
std::string load_error(const std::string& file, const ScenePose& pose) {
  try {
    (void)load_scene(file, {}, pose);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << file << " loaded";
  return "";
}

TEST(GltfAnimation, PosedCornersMatchTheNodeTreeEvaluatedByHandAtEveryTime) {
  const test::TempDir dir("gltfanim");
  const std::string file = dir.write("a.gltf", test::animated_gltf());
  const std::vector<float> corners = test::cube_corners();
  for (const double t : {-1.0, 0.0, 0.25, 0.5, 0.999, 1.0, 1.5, 1.75, 2.0, 7.0}) {
    const Scene s = load_scene(file, {}, {"", t});
    ASSERT_EQ(s.meshes.size(), 1u);
    ASSERT_EQ(s.meshes[0].positions.size(), 8u);
    for (std::size_t i = 0; i < 8; ++i)
      expect_near(s.meshes[0].positions[i],
                  spin_corner({corners[3 * i], corners[3 * i + 1], corners[3 * i + 2]}, t),
                  "t = " + std::to_string(t) + " corner " + std::to_string(i));
  }
}

TEST(GltfAnimation, LightsAndCamerasOfAnimatedNodesMoveWithThem) {
  const test::TempDir dir("gltfanim");
  const std::string file = dir.write("a.gltf", test::animated_gltf());
  for (const double t : {0.0, 0.5, 1.5, 3.0}) {
    const Scene s = load_scene(file, {}, {"spin", t});
    ASSERT_EQ(s.lights.size(), 1u);
    const long double tc = std::clamp(t, 0.0, 2.0);
    expect_near(s.lights[0].position, {t < 1 ? 0.0L : t < 2 ? 1.0L : 2.0L, 3, 0}, "light");
    expect_near(s.camera.position(), {0, 1 + tc / 2, 6 + tc}, "camera");
  }
}

TEST(GltfAnimation, AnimationsAreListedAndChosenByNameOrIndexTheFirstByDefault) {
  const test::TempDir dir("gltfanim");
  const std::string file = dir.write("a.gltf", test::animated_gltf());
  const Scene first = load_scene(file, {}, {"", 0.5});
  ASSERT_EQ(first.animations.size(), 2u);
  EXPECT_EQ(first.animations[0].name, "spin");
  EXPECT_EQ(first.animations[0].duration, 2.0);
  EXPECT_EQ(first.animations[1].name, "hop");
  EXPECT_EQ(first.animations[1].duration, 1.0);
  EXPECT_EQ(first.animation, 0);
  EXPECT_EQ(first.seconds, 0.5);
  for (const char* hop : {"hop", "1"}) {
    const Scene s = load_scene(file, {}, {hop, 0.5});
    EXPECT_EQ(s.animation, 1);
    // hop: node 0 at y = 1.5, not turned; the cube 0.5 above it, its scale 1
    expect_near(s.meshes[0].positions[0], {-0.5L, 1.5L + 0.5L - 0.5L, -0.5L}, hop);
  }
  EXPECT_NE(load_error(file, {"walk", 0}).find("has no animation 'walk' (its 2: #0 'spin', #1 'hop')"),
            std::string::npos);
  EXPECT_NE(load_error(file, {"2", 0}).find("has no animation '2'"), std::string::npos);
  const std::string obj = dir.write("t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_NE(load_error(obj, {"spin", 0}).find("has no animations (asked for 'spin')"),
            std::string::npos);
}

TEST(GltfAnimation, AStillFileIsTheSameAtEveryTime) {
  const test::TempDir dir("gltfanim");
  test::GltfFile f;
  f.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  const std::string file =
      dir.write("still.gltf", f.json(R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}])"));
  const Scene a = load_scene(file), b = load_scene(file, {}, {"", 12.5});
  EXPECT_TRUE(b.animations.empty());
  EXPECT_EQ(b.animation, -1);
  for (std::size_t i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(a.meshes[0].positions[i][k], b.meshes[0].positions[i][k]);
}

// A triangle with two morph targets (positions and normals), its mesh's weights, a node's
// weights and animated weights, against base + sum of weight x target by hand, moved by the
// node's translation.
TEST(GltfAnimation, MorphTargetsAddTheirWeightedDisplacementsStaticAndAnimated) {
  const test::TempDir dir("gltfmorph");
  test::GltfFile f;
  const std::vector<float> base = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::vector<float> t0 = {0, 0, 1, 0, 0, 2, 0, 0, 3}, t1 = {1, 1, 0, -1, 0, 0, 0.5f, 0, 0};
  const std::vector<float> normal = {0, 0, 1, 0, 0, 1, 0, 0, 1}, n0 = {1, 0, 0, 1, 0, 0, 1, 0, 0};
  f.floats(base, "VEC3", 3);                     // 0
  f.floats(normal, "VEC3", 3);                   // 1
  f.floats(t0, "VEC3", 3);                       // 2
  f.floats(n0, "VEC3", 3);                       // 3
  f.floats(t1, "VEC3", 3);                       // 4
  f.floats({0.0f, 1.0f}, "SCALAR", 1);           // 5: times
  f.floats({0.0f, 0.0f, 1.0f, 0.5f}, "SCALAR", 1);  // 6: weights, 2 a key
  const std::string mesh =
      R"(,"meshes":[{"weights":[0.5,0],"primitives":[{"attributes":{"POSITION":0,"NORMAL":1},)"
      R"("targets":[{"POSITION":2,"NORMAL":3},{"POSITION":4}]}]}],)";
  const std::string animated = dir.write(
      "animated.gltf",
      f.json(mesh + R"("nodes":[{"mesh":0,"translation":[0,0,5]}],"scenes":[{"nodes":[0]}],)"
                    R"("animations":[{"channels":[{"sampler":0,"target":{"node":0,"path":"weights"}}],)"
                    R"("samplers":[{"input":5,"output":6}]}])"));
  const std::string node_weights = dir.write(
      "node.gltf",
      f.json(mesh + R"("nodes":[{"mesh":0,"weights":[0.25,1]}],"scenes":[{"nodes":[0]}])"));
  const std::string mesh_weights = dir.write(
      "mesh.gltf", f.json(mesh + R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}])"));
  const auto check = [&](const std::string& file, double t, long double w0, long double w1,
                         long double dz) {
    const Scene s = load_scene(file, {}, {"", t});
    ASSERT_EQ(s.meshes.size(), 1u);
    const Mesh& m = s.meshes[0];
    for (std::size_t i = 0; i < 3; ++i) {
      Point want;
      for (std::size_t k = 0; k < 3; ++k)
        want[k] = base[3 * i + k] + w0 * t0[3 * i + k] + w1 * t1[3 * i + k] + (k == 2 ? dz : 0);
      expect_near(m.positions[i], want, file + " vertex " + std::to_string(i));
      const long double nx = w0, nz = 1, len = std::sqrt(nx * nx + nz * nz);
      expect_near(m.normals[i], {nx / len, 0, nz / len}, file + " normal");
    }
  };
  check(mesh_weights, 0.0, 0.5L, 0.0L, 0);
  check(node_weights, 0.0, 0.25L, 1.0L, 0);
  check(animated, 0.0, 0.0L, 0.0L, 5);
  check(animated, 0.5, 0.5L, 0.25L, 5);
  check(animated, 3.0, 1.0L, 0.5L, 5);
  // animated weights win over the node's
  const std::string both = dir.write(
      "both.gltf",
      f.json(mesh + R"("nodes":[{"mesh":0,"weights":[0.25,1]}],"scenes":[{"nodes":[0]}],)"
                    R"("animations":[{"channels":[{"sampler":0,"target":{"node":0,"path":"weights"}}],)"
                    R"("samplers":[{"input":5,"output":6}]}])"));
  check(both, 0.5, 0.5L, 0.25L, 0);
}

// A file without camera or lights is framed from its own node transforms, whatever time it
// is posed at: the view and the framing light stay put while the model moves; its warnings
// are printed once.
TEST(GltfAnimation, AFramedAnimatedFileKeepsItsCameraAndLightAtEveryTime) {
  const test::TempDir dir("gltfanim");
  test::GltfFile f;
  f.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  f.floats({0.0f, 2.0f}, "SCALAR", 1);
  f.floats({0, 0, 0, 4, 0, 0}, "VEC3", 3);
  const std::string file = dir.write(
      "framed.gltf",
      f.json(R"(,"extensionsUsed":["KHR_materials_clearcoat"],)"
             R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
             R"("animations":[{"channels":[{"sampler":0,"target":{"node":0,"path":"translation"}}],)"
             R"("samplers":[{"input":1,"output":2}]}])"));
  testing::internal::CaptureStderr();
  const Scene a = load_scene(file, {}, {"", 0.0});
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("ignores extension KHR_materials_clearcoat"), std::string::npos) << err;
  EXPECT_EQ(err.find("warning:"), err.rfind("warning:")) << err;  // once
  const Scene b = load_scene(file, {}, {"", 1.5});
  EXPECT_NE(a.meshes[0].positions[0][0], b.meshes[0].positions[0][0]);  // it moved: x 0, 3
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(a.camera.position()[k], b.camera.position()[k]);
    EXPECT_EQ(a.lights[0].position[k], b.lights[0].position[k]);
    EXPECT_EQ(a.framed_bounds->lo[k], b.framed_bounds->lo[k]);
  }
  EXPECT_EQ(a.lights[0].intensity, b.lights[0].intensity);
}

TEST(GltfAnimation, KeyframeNumbersAreBoundedWhenManyAnimationsShareOneLongSampler) {
  // 300 animations, each naming the same accessors of 60,000 keys (240 KB of data): read
  // once each they would be 300 x 240,000 numbers, more than io::kMaxGltfKeyValues.
  const test::TempDir dir("gltfanim");
  test::GltfFile f;
  f.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  std::vector<float> times(60000), values(180000, 0.5f);
  for (std::size_t i = 0; i < times.size(); ++i) times[i] = float(i) / 64.0f;
  f.floats(times, "SCALAR", 1);
  f.floats(values, "VEC3", 3);
  std::string animations;
  for (int a = 0; a < 300; ++a)
    animations += std::string(a ? "," : "") +
                  R"({"channels":[{"sampler":0,"target":{"node":0,"path":"translation"}}],)"
                  R"("samplers":[{"input":1,"output":2}]})";
  const std::string file = dir.write(
      "many.gltf", f.json(R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
                          R"("animations":[)" + animations + "]"));
  static_assert(300u * 240000u > io::kMaxGltfKeyValues);
  EXPECT_NE(load_error(file, {}).find("keyframe numbers"), std::string::npos);
}

}  // namespace
}  // namespace rt2
