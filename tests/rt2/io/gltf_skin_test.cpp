// glTF skins (rt2/io/gltf_scene.cpp, glTF 2.0 3.7.3): skinned vertices of an animated
// skeleton against the node tree, joint matrices and weighted blend evaluated by hand in
// double; a skeleton at its bind pose leaves the mesh as it is, whatever the skinned node's
// own transform; normals by the inverse transpose of the blended matrix, the winding turned
// back where it mirrors; a skinned mesh is never instanced. Malformed skins are in
// tests/hostile (gltf_skin_*). Each test names the property it checks.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <tuple>
#include <vector>

#include "rt2/io/scene_io.h"
#include "tests/rt2/io/gltf_file.h"
#include "tests/rt2/temp_dir.h"

namespace rt2 {
namespace {

// ---- the oracle: 4x4 matrices in double, column-major as glTF's (m[column * 4 + row]) -----

using M4 = std::array<double, 16>;
using V3 = std::array<double, 3>;

constexpr M4 kI = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

M4 mul(const M4& a, const M4& b) {
  M4 c{};
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 4; ++row)
      for (int k = 0; k < 4; ++k) c[col * 4 + row] += a[k * 4 + row] * b[col * 4 + k];
  return c;
}

M4 translate(const V3& t) {
  M4 m = kI;
  m[12] = t[0];
  m[13] = t[1];
  m[14] = t[2];
  return m;
}

M4 scale(const V3& s) {
  M4 m = kI;
  m[0] = s[0];
  m[5] = s[1];
  m[10] = s[2];
  return m;
}

// A turn by `angle` radians about axis 0 (x), 1 (y) or 2 (z), right-handed.
M4 turn(int axis, double angle) {
  const int a = (axis + 1) % 3, b = (axis + 2) % 3;
  M4 m = kI;
  m[a * 4 + a] = std::cos(angle);
  m[a * 4 + b] = std::sin(angle);
  m[b * 4 + a] = -std::sin(angle);
  m[b * 4 + b] = std::cos(angle);
  return m;
}

V3 place(const M4& m, const V3& p) {
  return {m[0] * p[0] + m[4] * p[1] + m[8] * p[2] + m[12],
          m[1] * p[0] + m[5] * p[1] + m[9] * p[2] + m[13],
          m[2] * p[0] + m[6] * p[1] + m[10] * p[2] + m[14]};
}

// The inverse transpose of the upper 3x3 of m applied to n, normalized.
V3 normal_by(const M4& m, const V3& n) {
  const auto e = [&](int r, int c) { return m[c * 4 + r]; };
  // inverse = adjugate / det; inverse transpose = cofactor matrix / det
  double cof[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      cof[r][c] = e((r + 1) % 3, (c + 1) % 3) * e((r + 2) % 3, (c + 2) % 3) -
                  e((r + 1) % 3, (c + 2) % 3) * e((r + 2) % 3, (c + 1) % 3);
  const double det = e(0, 0) * cof[0][0] + e(0, 1) * cof[0][1] + e(0, 2) * cof[0][2];
  V3 out{};
  for (int r = 0; r < 3; ++r)
    out[std::size_t(r)] = (cof[r][0] * n[0] + cof[r][1] * n[1] + cof[r][2] * n[2]) / det;
  const double len = std::sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2]);
  return {out[0] / len, out[1] / len, out[2] / len};
}

double det3(const M4& m) {
  return m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) +
         m[8] * (m[1] * m[6] - m[5] * m[2]);
}

// The weighted blend of joint matrices.
M4 blend(const std::vector<M4>& joints, const std::array<int, 4>& index,
         const std::array<float, 4>& weight) {
  M4 m{};
  for (std::size_t k = 0; k < 4; ++k)
    for (std::size_t e = 0; e < 16; ++e)
      m[e] += double(weight[k]) * joints[std::size_t(index[k])][e];
  return m;
}

std::vector<float> floats_of(const M4& m) { return std::vector<float>(m.begin(), m.end()); }
M4 rounded(const M4& m) {
  M4 r;
  for (std::size_t e = 0; e < 16; ++e) r[e] = double(float(m[e]));
  return r;
}

void expect_near(const vec4& got, const V3& want, double tolerance, const std::string& what) {
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(double(got[k]), want[std::size_t(k)], tolerance) << what << " axis " << k;
}

// ---- an arm of three joints ---------------------------------------------------------------

// A strip of 8 vertices along x (x = 0 ... 3, y = 0 and 1), one morph target, skinned by
// joints 0, 1, 2 (nodes 1, 2, 3: a chain) with weights that move from the first joint to the
// last along the strip.
struct Arm {
  std::vector<float> positions, target;
  std::vector<std::array<int, 4>> joints;
  std::vector<std::array<float, 4>> weights;
  double morph_weight = 0.5;
  // The joints' rest transforms (translation, and node 3's scale) and inverse bind matrices
  // as the file holds them (floats).
  std::vector<M4> inverse_bind;
};

Arm arm() {
  Arm a;
  const std::array<std::array<float, 4>, 4> w = {{{1, 0, 0, 0},
                                                  {0.5f, 0.5f, 0, 0},
                                                  {0.25f, 0.5f, 0.25f, 0},
                                                  {0, 0.25f, 0.75f, 0}}};
  for (int i = 0; i < 4; ++i)
    for (int y = 0; y < 2; ++y) {
      a.positions.insert(a.positions.end(), {float(i), float(y), 0.1f * float(i * y)});
      a.target.insert(a.target.end(), {0.1f * float(i), 0.2f, -0.3f * float(y)});
      a.joints.push_back({0, 1, 2, 0});
      a.weights.push_back(w[std::size_t(i)]);
    }
  // bind pose: node 1 at the origin, node 2 at x = 1, node 3 at x = 2 scaled 1.5 in y
  a.inverse_bind = {kI, translate({-1, 0, 0}),
                    rounded(mul(scale({1, 1 / 1.5, 1}), translate({-2, 0, 0})))};
  return a;
}

// Node 1's rotation about z (LINEAR) keys at 0, 1, 2 s; node 1's translation CUBICSPLINE
// (keys at 0 and 2 s); node 2's rotation about y LINEAR (0 and 2 s); node 3's translation
// LINEAR (0 and 2 s).
constexpr double kPi = 3.14159265358979323846;
constexpr std::array<double, 3> kRootAngles = {0, kPi / 3, kPi / 6};
constexpr V3 kRootFrom = {0, 0, 0}, kRootTo = {1, 2, 0}, kRootOut = {1, 0, 0}, kRootIn = {0, -1, 0};
constexpr double kMidAngle = kPi / 2;
constexpr V3 kTipFrom = {1, 0, 0}, kTipTo = {1, 1, 0};

std::string arm_gltf(const Arm& a) {
  test::GltfFile f;
  f.floats(a.positions, "VEC3", 3);  // 0
  f.floats(a.target, "VEC3", 3);     // 1
  std::vector<std::uint16_t> joints;
  std::vector<float> weights;
  for (std::size_t i = 0; i < a.joints.size(); ++i)
    for (std::size_t k = 0; k < 4; ++k) {
      joints.push_back(std::uint16_t(a.joints[i][k]));
      weights.push_back(a.weights[i][k]);
    }
  f.accessor(joints, 5123, "VEC4", a.joints.size());  // 2
  f.floats(weights, "VEC4", 4);                        // 3
  std::vector<float> ibm;
  for (const M4& m : a.inverse_bind)
    for (const float x : floats_of(m)) ibm.push_back(x);
  f.floats(ibm, "MAT4", 16);  // 4
  std::vector<unsigned> faces;
  for (unsigned i = 0; i < 3; ++i) {
    const unsigned b = 2 * i;
    faces.insert(faces.end(), {b, b + 2, b + 1, b + 1, b + 2, b + 3});
  }
  f.accessor(faces, 5125, "SCALAR", faces.size());  // 5
  const auto quat_z = [](double angle) {
    return std::vector<float>{0, 0, float(std::sin(angle / 2)), float(std::cos(angle / 2))};
  };
  std::vector<float> root_turns;
  for (const double angle : kRootAngles)
    for (const float x : quat_z(angle)) root_turns.push_back(x);
  f.floats({0, 1, 2}, "SCALAR", 1);       // 6
  f.floats(root_turns, "VEC4", 4);        // 7
  f.floats({0, 2}, "SCALAR", 1);          // 8
  std::vector<float> cubic;               // in-tangent, value, out-tangent per key
  for (const V3& v : {V3{0, 0, 0}, kRootFrom, kRootOut, kRootIn, kRootTo, V3{0, 0, 0}})
    for (const double x : v) cubic.push_back(float(x));
  f.floats(cubic, "VEC3", 3);  // 9
  const float h = float(std::sin(kMidAngle / 2)), c = float(std::cos(kMidAngle / 2));
  f.floats({0, 0, 0, 1, 0, h, 0, c}, "VEC4", 4);  // 10
  std::vector<float> tip;
  for (const V3& v : {kTipFrom, kTipTo})
    for (const double x : v) tip.push_back(float(x));
  f.floats(tip, "VEC3", 3);  // 11
  return f.json(
      R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0,"JOINTS_0":2,"WEIGHTS_0":3},)"
      R"("indices":5,"targets":[{"POSITION":1}]}]}],)"
      R"("skins":[{"joints":[1,2,3],"inverseBindMatrices":4,"skeleton":1}],)"
      R"("nodes":[{"mesh":0,"skin":0,"weights":[0.5],"translation":[10,0,0],)"
      R"("rotation":[0,0.6,0,0.8]},{"children":[2]},{"translation":[1,0,0],"children":[3]},)"
      R"({"translation":[1,0,0],"scale":[1,1.5,1]}],"scenes":[{"nodes":[0,1]}],)"
      R"("animations":[{"channels":[)"
      R"({"sampler":0,"target":{"node":1,"path":"rotation"}},)"
      R"({"sampler":1,"target":{"node":1,"path":"translation"}},)"
      R"({"sampler":2,"target":{"node":2,"path":"rotation"}},)"
      R"({"sampler":3,"target":{"node":3,"path":"translation"}}],"samplers":[)"
      R"({"input":6,"output":7},{"input":8,"output":9,"interpolation":"CUBICSPLINE"},)"
      R"({"input":8,"output":10},{"input":8,"output":11}]}])");
}

// The arm's joint matrices at `t` by hand: each key sampled as glTF says (a turn about one
// axis slerps as its angle), local matrices T · R · S, world matrices down the chain, times
// the inverse bind matrices.
std::vector<M4> arm_joints(const Arm& a, double t) {
  const double tc = std::clamp(t, 0.0, 2.0);
  const double root_angle = tc < 1 ? kRootAngles[0] + tc * (kRootAngles[1] - kRootAngles[0])
                                   : kRootAngles[1] + (tc - 1) * (kRootAngles[2] - kRootAngles[1]);
  // Hermite: p(s) = h00 p0 + h10 d m0 + h01 p1 + h11 d m1, d = 2 s the key interval
  const double s = tc / 2, d = 2;
  const double h00 = 2 * s * s * s - 3 * s * s + 1, h10 = s * s * s - 2 * s * s + s,
               h01 = -2 * s * s * s + 3 * s * s, h11 = s * s * s - s * s;
  V3 root_at;
  V3 tip_at;
  for (std::size_t k = 0; k < 3; ++k) {
    root_at[k] = h00 * kRootFrom[k] + h10 * d * kRootOut[k] + h01 * kRootTo[k] + h11 * d * kRootIn[k];
    tip_at[k] = kTipFrom[k] + s * (kTipTo[k] - kTipFrom[k]);
  }
  const M4 w1 = mul(translate(root_at), turn(2, root_angle));
  const M4 w2 = mul(w1, mul(translate({1, 0, 0}), turn(1, s * kMidAngle)));
  const M4 w3 = mul(w2, mul(translate(tip_at), scale({1, 1.5, 1})));
  return {mul(w1, a.inverse_bind[0]), mul(w2, a.inverse_bind[1]), mul(w3, a.inverse_bind[2])};
}

TEST(GltfSkin, SkinnedVerticesMatchTheJointsBlendedByHandAfterMorphingAtEveryTime) {
  const test::TempDir dir("gltfskin");
  const Arm a = arm();
  const std::string file = dir.write("arm.gltf", arm_gltf(a));
  for (const double t : {-0.5, 0.0, 0.3, 0.999, 1.0, 1.25, 1.7, 2.0, 3.0}) {
    const Scene s = load_scene(file, {}, {"", t});
    ASSERT_EQ(s.meshes.size(), 1u);
    ASSERT_EQ(s.meshes[0].positions.size(), 8u);
    EXPECT_EQ(s.meshes[0].faces.size(), 6u);
    const std::vector<M4> joints = arm_joints(a, t);
    for (std::size_t i = 0; i < 8; ++i) {
      V3 p;
      for (std::size_t k = 0; k < 3; ++k)
        p[k] = double(a.positions[3 * i + k]) + a.morph_weight * double(a.target[3 * i + k]);
      expect_near(s.meshes[0].positions[i], place(blend(joints, a.joints[i], a.weights[i]), p),
                  2e-6, "t = " + std::to_string(t) + " vertex " + std::to_string(i));
    }
  }
}

// ---- a skeleton at its bind pose ----------------------------------------------------------

// Joints placed where their inverse bind matrices undo exactly (a turn by 180 degrees, a
// translation, a scale by 2): every joint matrix is the identity, whatever the weights.
TEST(GltfSkin, ASkeletonAtItsBindPoseLeavesTheMeshAsItIsWhateverTheSkinnedNodesTransform) {
  const test::TempDir dir("gltfskin");
  const std::vector<float> positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0.5f};
  const std::vector<float> normals = {0, 0, 1, 0, 0.6f, 0.8f, 0.6f, 0, 0.8f, 0, 0, 1};
  // node 1: translation 1 2 3, a turn by pi about z; node 2 under it: 0.5 along x, scale 2.
  // Their world matrices' inverses, exact (turn(2, pi), its sines rounded to 0, is its own):
  M4 r = turn(2, kPi);
  for (double& x : r) x = std::round(x);
  const M4 ibm1 = mul(r, translate({-1, -2, -3}));
  const M4 ibm2 = mul(mul(scale({0.5, 0.5, 0.5}), translate({-0.5, 0, 0})), ibm1);
  test::GltfFile f;
  f.floats(positions, "VEC3", 3);  // 0
  f.floats(normals, "VEC3", 3);    // 1
  f.accessor(std::vector<std::uint8_t>{0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0}, 5121,
             "VEC4", 4);  // 2
  f.accessor(std::vector<std::uint8_t>{255, 0, 0, 0, 128, 127, 0, 0, 255, 0, 0, 0, 64, 191, 0, 0},
             5121, "VEC4", 4, true);  // 3
  std::vector<float> ibm = floats_of(ibm1);
  for (const float x : floats_of(ibm2)) ibm.push_back(x);
  f.floats(ibm, "MAT4", 16);  // 4
  f.accessor(std::vector<unsigned>{0, 1, 2, 2, 1, 3}, 5125, "SCALAR", 6);  // 5
  const std::string mesh =
      R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1,"JOINTS_0":2,)"
      R"("WEIGHTS_0":3},"indices":5}]}],)";
  const std::string skinned = dir.write(
      "skinned.gltf",
      f.json(mesh + R"("skins":[{"joints":[1,2],"inverseBindMatrices":4}],)"
                    R"("nodes":[{"mesh":0,"skin":0,"translation":[5,5,5],"scale":[3,-3,3]},)"
                    R"({"translation":[1,2,3],"rotation":[0,0,1,0],"children":[2]},)"
                    R"({"translation":[0.5,0,0],"scale":[2,2,2]}],"scenes":[{"nodes":[0,1]}])"));
  const std::string plain = dir.write(
      "plain.gltf", f.json(mesh + R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}])"));
  const Scene a = load_scene(skinned), b = load_scene(plain);
  ASSERT_EQ(a.meshes.size(), 1u);
  ASSERT_EQ(b.meshes.size(), 1u);
  ASSERT_EQ(a.meshes[0].positions.size(), 4u);
  ASSERT_EQ(a.meshes[0].normals.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(a.meshes[0].positions[i][k], b.meshes[0].positions[i][k], 1e-6) << i;
      EXPECT_NEAR(a.meshes[0].normals[i][k], b.meshes[0].normals[i][k], 1e-6) << i;
    }
  EXPECT_EQ(a.meshes[0].faces, b.meshes[0].faces);  // the node's mirroring scale is ignored too
}

// ---- normals ------------------------------------------------------------------------------

// A triangle with slanted normals under two joints: one turned and scaled unevenly, one
// mirroring; the middle corner blends them. No inverseBindMatrices: identities.
TEST(GltfSkin, NormalsFollowTheInverseTransposeOfTheBlendAndMirroringTurnsTheWinding) {
  const test::TempDir dir("gltfskin");
  const std::vector<float> positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::vector<float> normals = {0, 0, 1, 0.6f, 0, 0.8f, 0, 0.6f, 0.8f};
  const std::vector<std::array<int, 4>> joints = {{0, 0, 0, 0}, {0, 1, 0, 0}, {1, 0, 0, 0}};
  const auto file_with = [&](const std::string& name, const std::array<float, 4>& middle,
                             const std::string& second_scale) {
    const std::vector<std::array<float, 4>> weights = {{1, 0, 0, 0}, middle, {1, 0, 0, 0}};
    test::GltfFile f;
    f.floats(positions, "VEC3", 3);
    f.floats(normals, "VEC3", 3);
    std::vector<std::uint8_t> j;
    std::vector<float> w;
    for (std::size_t i = 0; i < 3; ++i)
      for (std::size_t k = 0; k < 4; ++k) {
        j.push_back(std::uint8_t(joints[i][k]));
        w.push_back(weights[i][k]);
      }
    f.accessor(j, 5121, "VEC4", 3);
    f.floats(w, "VEC4", 4);
    return dir.write(
        name,
        f.json(R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1,)"
               R"("JOINTS_0":2,"WEIGHTS_0":3}}]}],"skins":[{"joints":[1,2]}],)"
               R"("nodes":[{"mesh":0,"skin":0},)"
               R"({"rotation":[0.25881904,0,0,0.96592583],"scale":[1,3,0.5]},)"
               R"({"translation":[0,0,2],"scale":)" + second_scale + "}]," +
               R"("scenes":[{"nodes":[0,1,2]}])"));
  };
  // joint 0: a turn of 30 degrees about x (the quaternion rounded to float), scaled 1, 3, 0.5
  const double half = std::atan2(0.25881904, 0.96592583);
  const M4 j0 = mul(turn(0, 2 * half), scale({1, 3, 0.5}));
  for (const auto& [name, middle, second, mirror] :
       {std::tuple{"even.gltf", std::array<float, 4>{0.5f, 0.5f, 0, 0}, V3{2, 1, 1}, false},
        std::tuple{"mirror.gltf", std::array<float, 4>{0.25f, 0.75f, 0, 0}, V3{-1, 1, 1}, true},
        std::tuple{"mixed.gltf", std::array<float, 4>{0.75f, 0.25f, 0, 0}, V3{-1, 1, 1}, false}}) {
    const std::string scale_json = "[" + std::to_string(second[0]) + "," +
                                   std::to_string(second[1]) + "," + std::to_string(second[2]) + "]";
    const Scene s = load_scene(file_with(name, middle, scale_json));
    const M4 j1 = mul(translate({0, 0, 2}), scale(second));
    const std::vector<M4> js = {j0, j1};
    ASSERT_EQ(s.meshes.size(), 1u) << name;
    ASSERT_EQ(s.meshes[0].normals.size(), 3u) << name;
    int mirrored = 0;
    for (std::size_t i = 0; i < 3; ++i) {
      const std::array<float, 4> w =
          i == 1 ? middle : std::array<float, 4>{1, 0, 0, 0};
      const M4 m = blend(js, joints[i], w);
      mirrored += det3(m) < 0;
      const V3 p = {positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]};
      const V3 n = {normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]};
      expect_near(s.meshes[0].positions[i], place(m, p), 1e-6, std::string(name) + " position");
      expect_near(s.meshes[0].normals[i], normal_by(m, n), 1e-6, std::string(name) + " normal");
    }
    EXPECT_EQ(mirrored >= 2, mirror) << name;
    ASSERT_EQ(s.meshes[0].faces.size(), 1u);
    const std::array<std::uint32_t, 3> want =
        mirror ? std::array<std::uint32_t, 3>{0, 2, 1} : std::array<std::uint32_t, 3>{0, 1, 2};
    EXPECT_EQ(s.meshes[0].faces[0], want) << name;
  }
}

// ---- instancing ---------------------------------------------------------------------------

TEST(GltfSkin, ASkinnedNodesMeshIsItsOwnWhileThePlainNodesOfTheSameMeshShareIt) {
  const test::TempDir dir("gltfskin");
  test::GltfFile f;
  f.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  f.accessor(std::vector<std::uint8_t>(12, 0), 5121, "VEC4", 3);
  f.floats({1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4", 4);
  const std::string file = dir.write(
      "shared.gltf",
      f.json(R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0,"JOINTS_0":1,)"
             R"("WEIGHTS_0":2}}]}],"skins":[{"joints":[3]}],)"
             R"("nodes":[{"mesh":0,"skin":0},{"mesh":0,"translation":[2,0,0]},)"
             R"({"mesh":0,"translation":[4,0,0]},{"translation":[0,0,7]}],)"
             R"("scenes":[{"nodes":[0,1,2,3]}])"));
  const Scene s = load_scene(file);
  ASSERT_EQ(s.meshes.size(), 1u);  // the skinned node's, moved by its joint
  expect_near(s.meshes[0].positions[1], {1, 0, 7}, 0, "skinned");
  EXPECT_EQ(s.instanced_meshes.size(), 1u);
  EXPECT_EQ(s.instances.size(), 2u);
}

}  // namespace
}  // namespace rt2
