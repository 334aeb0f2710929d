// rt2::ScenePoser (rt2/io/scene_io.h): a scene that moves, posed again from its parsed file,
// against a fresh load at the same time (bit for bit), and the order of errors in the pass
// that places a primitive's vertices (on several threads for a large one). Each test names the property it
// checks.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "rt2/base/error.h"
#include "rt2/io/scene_io.h"
#include "tests/rt2/io/animated_gltf.h"
#include "tests/rt2/io/gltf_file.h"
#include "tests/rt2/temp_dir.h"

namespace rt2 {
namespace {

template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

template <class T>
bool same_bytes(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

// What a render reads of a loaded scene, compared byte for byte.
void expect_same_scene(const Scene& a, const Scene& b, const std::string& what) {
  ASSERT_EQ(a.meshes.size(), b.meshes.size()) << what;
  for (std::size_t m = 0; m < a.meshes.size(); ++m) {
    EXPECT_TRUE(same_bytes(a.meshes[m].positions, b.meshes[m].positions)) << what << " mesh " << m;
    EXPECT_TRUE(same_bytes(a.meshes[m].normals, b.meshes[m].normals)) << what << " mesh " << m;
    EXPECT_TRUE(same_bytes(a.meshes[m].faces, b.meshes[m].faces)) << what << " mesh " << m;
    EXPECT_TRUE(same_bytes(a.meshes[m].face_materials, b.meshes[m].face_materials)) << what;
  }
  ASSERT_EQ(a.instances.size(), b.instances.size()) << what;
  for (std::size_t i = 0; i < a.instances.size(); ++i)
    EXPECT_TRUE(same_bytes(a.instances[i].to_world, b.instances[i].to_world)) << what;
  ASSERT_EQ(a.lights.size(), b.lights.size()) << what;
  for (std::size_t i = 0; i < a.lights.size(); ++i) {
    EXPECT_TRUE(same_bytes(a.lights[i].position, b.lights[i].position)) << what;
    EXPECT_EQ(a.lights[i].intensity, b.lights[i].intensity) << what;
  }
  EXPECT_TRUE(same_bytes(a.camera.position(), b.camera.position())) << what;
  EXPECT_TRUE(same_bytes(a.camera.forward(), b.camera.forward())) << what;
  EXPECT_EQ(a.animation, b.animation) << what;
  EXPECT_EQ(a.seconds, b.seconds) << what;
}

// The message of the rt2::Error loading `file` throws ("" if it loads).
std::string load_error(const std::string& file) {
  try {
    (void)load_scene(file);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << file << " loaded";
  return "";
}

// A strip of `pairs` x 2 vertices along x, bound to two joints (node 1 the root, node 2 its
// child one unit along x, turning about z over 0 ... 2 s); each vertex's weights blend the
// joints by its x. Vertex `huge` (if any) is far out, where node 0's scale of 10 takes it past
// float range.
std::string strip_gltf(std::size_t pairs, const std::vector<std::size_t>& huge = {}) {
  test::GltfFile f;
  std::vector<float> positions, weights;
  std::vector<std::uint8_t> joints;
  for (std::size_t i = 0; i < pairs; ++i)
    for (int side = 0; side < 2; ++side) {
      const float x = float(i) / float(pairs - 1) * 2.0f;
      positions.insert(positions.end(), {x, float(side) * 0.1f, 0.0f});
      const float w = std::fmin(x / 2.0f, 1.0f);
      weights.insert(weights.end(), {1.0f - w, w, 0.0f, 0.0f});
      joints.insert(joints.end(), {0, 1, 0, 0});
    }
  for (const std::size_t v : huge) positions[3 * v] = 3e38f;
  f.floats(positions, "VEC3", 3);                   // 0
  f.accessor(joints, 5121, "VEC4", joints.size() / 4);  // 1
  f.floats(weights, "VEC4", 4);                      // 2
  std::vector<unsigned> faces;
  for (unsigned i = 0; i + 1 < pairs; ++i) {
    const unsigned b = 2 * i;
    faces.insert(faces.end(), {b, b + 2, b + 1, b + 1, b + 2, b + 3});
  }
  f.accessor(faces, 5125, "SCALAR", faces.size());  // 3
  f.floats({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,    // joint 0 at the origin
            1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -1, 0, 0, 1},  // joint 1 at x = 1
           "MAT4", 16);                                        // 4
  f.floats({0, 2}, "SCALAR", 1);                               // 5
  const float s = float(std::sin(0.4)), c = float(std::cos(0.4));
  f.floats({0, 0, 0, 1, 0, 0, s, c}, "VEC4", 4);  // 6
  return f.json(
      R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0,"JOINTS_0":1,"WEIGHTS_0":2},)"
      R"("indices":3}]}],"skins":[{"joints":[1,2],"inverseBindMatrices":4}],)"
      R"("nodes":[{"mesh":0,"skin":0,"scale":[10,10,10]},{"children":[2],"scale":[10,10,10]},)"
      R"({"translation":[1,0,0]}],"scenes":[{"nodes":[0,1]}],)"
      R"("animations":[{"channels":[{"sampler":0,"target":{"node":2,"path":"rotation"}}],)"
      R"("samplers":[{"input":5,"output":6}]}])");
}

TEST(ScenePoser, APoseIsTheFreshLoadAtItsTimeBitForBit) {
  const test::TempDir dir("poser");
  // node animations with a light and a camera on animated nodes, the first and the second;
  // a skinned primitive large enough to be placed on several threads, without a camera or
  // lights (framed)
  const std::string spin = dir.write("spin.gltf", test::animated_gltf());
  const std::string strip = dir.write("strip.gltf", strip_gltf(20000));
  for (const auto& [file, animation] : {std::pair{spin, std::string()}, std::pair{spin, std::string("hop")},
                                        std::pair{strip, std::string()}}) {
    {
      ScenePoser poser;
      const Scene first = load_scene(file, {}, {animation, 0.25}, &poser);
      ASSERT_TRUE(poser) << file;
      expect_same_scene(poser.at(0.25), first, file);
      for (const double t : {0.0, 0.7, 1.5, 2.0, 3.5, -1.0}) {
        const Scene fresh = load_scene(file, {}, {animation, t});
        expect_same_scene(poser.at(t), fresh, file + " at " + std::to_string(t));
      }
    }
  }
}

TEST(ScenePoser, AStillSceneHasNoPoser) {
  const test::TempDir dir("poser");
  test::GltfFile f;
  f.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  const std::string file =
      dir.write("still.gltf", f.json(R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}])"));
  ScenePoser poser;
  (void)load_scene(file, {}, {}, &poser);
  EXPECT_FALSE(poser);
  EXPECT_THROW((void)poser.at(1.0), Error);
}

// Vertices are placed on several threads in runs; whichever run meets its bad vertex first,
// the message names the lowest one, as a loop in order would.
TEST(ScenePoser, TheFirstBadVertexOfALargePrimitiveIsNamedWhicheverThreadMeetsIt) {
  const test::TempDir dir("poser");
  const std::size_t pairs = 20000;  // 40000 vertices: runs of 20000 on two threads
  const std::string file = dir.write("bad.gltf", strip_gltf(pairs, {39990, 30001, 19999}));
  for (int round = 0; round < 4; ++round) {
    const std::string error = load_error(file);
    EXPECT_NE(error.find("POSITION 19999 is not a finite float"), std::string::npos) << error;
  }
}

// A primitive whose vertex and NORMAL accessor are both at fault names the vertex, as when
// normals were read after the positions.
TEST(ScenePoser, ABadVertexIsNamedBeforeABadNormalAccessor) {
  const test::TempDir dir("poser");
  test::GltfFile f;
  f.floats({3e38f, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);  // 0: vertex 0 overflows at scale 10
  f.floats({0, 0, 1, 0, 0, 1}, "VEC3", 3);                // 1: two normals for three vertices
  const std::string file = dir.write(
      "bad.gltf", f.json(R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1}}]}],)"
                         R"("nodes":[{"mesh":0,"scale":[10,10,10]}],"scenes":[{"nodes":[0]}])"));
  const std::string error = load_error(file);
  EXPECT_NE(error.find("POSITION 0 is not a finite float"), std::string::npos) << error;
}

}  // namespace
}  // namespace rt2
