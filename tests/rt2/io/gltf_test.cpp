// tests/rt2/io/gltf_test.cpp — glTF 2.0 loading (rt2/io/gltf_scene.h through rt2::load_scene):
// small files written by the tests (test::GltfFile builds their buffers and accessors), as
// JSON with an embedded base64 buffer and as binary .glb; and every glTF file of Debian's
// assimp-testmodels, each of which must load or fail with one rt2::Error line.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "rt2/base/error.h"
#include "rt2/image/image_compare.h"
#include "rt2/io/scene_io.h"
#include "tests/rt2/error_of.h"
#include "tests/rt2/io/gltf_file.h"
#include "tests/rt2/temp_dir.h"
#include "tests/rt2/test_util.h"

namespace rt2 {
namespace {

namespace fs = std::filesystem;
using test::GltfFile;

// A triangle (0,0,0), (1,0,0), (0,1,0) with normals +z and texture coordinates.
GltfFile triangle() {
  GltfFile f;
  f.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);  // accessor 0: POSITION
  f.floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);  // accessor 1: NORMAL
  f.floats({0, 0.25f, 1, 0, 0.5f, 1}, "VEC2", 2);    // accessor 2: TEXCOORD_0
  return f;
}

const std::string kTriangleMesh =
    R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2}}]}])";

void expect_near(const vec4& v, float x, float y, float z, float eps = 1e-5f) {
  EXPECT_NEAR(v[0], x, eps);
  EXPECT_NEAR(v[1], y, eps);
  EXPECT_NEAR(v[2], z, eps);
}

TEST(Gltf, NodeTransformsComposeParentTimesChild) {
  const test::TempDir dir("gltf");
  // Parent: translation (10, 0, 0). Child: translation (1, 2, 3), 90° about z, scale 2.
  const double s = std::sqrt(0.5);
  const std::string nodes =
      R"(,"scenes":[{"nodes":[0]}],"nodes":[{"translation":[10,0,0],"children":[1]},)"
      R"({"mesh":0,"translation":[1,2,3],"rotation":[0,0,)" +
      std::to_string(s) + "," + std::to_string(s) + R"(],"scale":[2,2,2]}])";
  const Scene scene = load_scene(dir.write("t.gltf", triangle().json(kTriangleMesh + nodes)));
  ASSERT_EQ(scene.meshes.size(), 1u);
  const Mesh& m = scene.meshes[0];
  ASSERT_EQ(m.positions.size(), 3u);
  expect_near(m.positions[0], 11, 2, 3);
  expect_near(m.positions[1], 11, 4, 3);  // (1,0,0) scaled to (2,0,0), turned to (0,2,0)
  expect_near(m.positions[2], 9, 2, 3);
  ASSERT_EQ(m.normals.size(), 3u);
  expect_near(m.normals[0], 0, 0, 1);
}

// A mesh that several nodes place is read once and placed by instances; the picture is
// that of the same nodes placing copies of it (each copy read into the world).
TEST(Gltf, AMeshSharedByNodesBecomesInstancesThatRenderAsCopies) {
  const test::TempDir dir("gltf");
  GltfFile f;
  // a tetrahedron with a normal per vertex (pointing away from its centre)
  f.floats({0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1}, "VEC3", 3);
  const float k = 1.0f / std::sqrt(3.0f);
  f.floats({-k, -k, -k, 1, 0, 0, 0, 1, 0, 0, 0, 1}, "VEC3", 3);
  f.accessor(std::vector<std::uint16_t>{0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3}, 5123, "SCALAR", 12);
  const std::string primitive = R"({"primitives":[{"attributes":{"POSITION":0,"NORMAL":1},"indices":2}]})";
  const std::string placements =
      R"("nodes":[{"mesh":M0,"translation":[-1.5,0,0]},)"
      R"({"mesh":M1,"rotation":[0,0.38268343,0,0.92387953],"scale":[1,2,1]},)"
      R"({"mesh":M2,"translation":[1.5,0,0],"scale":[-1,1,1]},)"
      R"({"camera":0,"translation":[0.2,1.5,6],"rotation":[-0.1305262,0,0,0.9914449]}],)"
      R"("cameras":[{"type":"perspective","perspective":{"yfov":0.8,"znear":0.1}}],)"
      R"("scenes":[{"nodes":[0,1,2,3]}])";
  const auto file = [&](bool shared) {
    std::string nodes = placements;
    for (int i = 0; i < 3; ++i)
      nodes.replace(nodes.find("M" + std::to_string(i)), 2, shared ? "0" : std::to_string(i));
    const std::string meshes = shared ? primitive : primitive + "," + primitive + "," + primitive;
    return f.json(R"(,"meshes":[)" + meshes + "]," + nodes);
  };
  const Scene inst = load_scene(dir.write("shared.gltf", file(true)));
  Scene flat = load_scene(dir.write("copies.gltf", file(false)));
  // The framing light stands by the scene's box, which the instances' boxes (their mesh's box
  // placed) make a little larger: the same light for both.
  flat.lights = inst.lights;
  ASSERT_EQ(inst.instanced_meshes.size(), 1u);
  EXPECT_EQ(inst.instances.size(), 3u);
  EXPECT_TRUE(inst.meshes.empty());
  EXPECT_EQ(flat.meshes.size(), 3u);
  EXPECT_TRUE(flat.instances.empty());
  EXPECT_EQ(inst.placed_triangle_count(), flat.triangle_count());
  RenderSettings st;
  st.width = 120;
  st.height = 90;
  st.depth = 4;
  const ImageError e = compare_images(test::render_scene(inst, st), test::render_scene(flat, st));
  EXPECT_GT(e.psnr, 60.0);
}

TEST(Gltf, NormalsTakeTheInverseTransposeAndAreRenormalized) {
  const test::TempDir dir("gltf");
  GltfFile f;
  f.floats({0, 0, 0, 1, 0, 0, 0, 0, 1}, "VEC3", 3);
  f.floats({0.6f, 0.8f, 0, 0.6f, 0.8f, 0, 0.6f, 0.8f, 0}, "VEC3", 3);
  const std::string rest =
      R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1}}]}],)"
      R"("nodes":[{"mesh":0,"scale":[1,2,1]}],"scenes":[{"nodes":[0]}])";
  const Scene scene = load_scene(dir.write("n.gltf", f.json(rest)));
  ASSERT_EQ(scene.meshes.size(), 1u);
  // M^-T (0.6, 0.8, 0) = (0.6, 0.4, 0), normalized.
  const float len = std::sqrt(0.36f + 0.16f);
  expect_near(scene.meshes[0].normals[0], 0.6f / len, 0.4f / len, 0);
}

TEST(Gltf, FlipsTexcoordV) {
  const test::TempDir dir("gltf");
  const Scene scene = load_scene(dir.write("uv.gltf", triangle().json(kTriangleMesh)));
  ASSERT_EQ(scene.meshes.size(), 1u);
  const auto& uv = scene.meshes[0].texcoords;
  ASSERT_EQ(uv.size(), 3u);
  EXPECT_FLOAT_EQ(uv[0][0], 0.0f);
  EXPECT_FLOAT_EQ(uv[0][1], 0.75f);
  EXPECT_FLOAT_EQ(uv[1][1], 1.0f);
  EXPECT_FLOAT_EQ(uv[2][1], 0.0f);
}

TEST(Gltf, ReadsNormalizedIntegerTexcoords) {
  const test::TempDir dir("gltf");
  GltfFile f;
  f.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  f.accessor(std::vector<std::uint16_t>{0, 65535, 65535, 0, 0, 0}, 5123, "VEC2", 3, true);
  const std::string rest =
      R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1}}]}])";
  const Scene scene = load_scene(dir.write("uv16.gltf", f.json(rest)));
  const auto& uv = scene.meshes.at(0).texcoords;
  ASSERT_EQ(uv.size(), 3u);
  EXPECT_FLOAT_EQ(uv[0][1], 0.0f);  // v = 1
  EXPECT_FLOAT_EQ(uv[1][0], 1.0f);
  EXPECT_FLOAT_EQ(uv[1][1], 1.0f);  // v = 0
}

TEST(Gltf, ReadsIndicesOfEveryComponentType) {
  for (const int type : {5121, 5123, 5125}) {
    const test::TempDir dir("gltf");
    GltfFile f;
    f.floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3", 3);
    const std::vector<unsigned> idx = {0, 1, 2, 0, 2, 3};
    if (type == 5121)
      f.accessor(std::vector<std::uint8_t>(idx.begin(), idx.end()), type, "SCALAR", 6);
    if (type == 5123)
      f.accessor(std::vector<std::uint16_t>(idx.begin(), idx.end()), type, "SCALAR", 6);
    if (type == 5125)
      f.accessor(std::vector<std::uint32_t>(idx.begin(), idx.end()), type, "SCALAR", 6);
    const std::string rest =
        R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}])";
    const Scene scene = load_scene(dir.write("quad.gltf", f.json(rest)));
    ASSERT_EQ(scene.meshes.size(), 1u) << type;
    const Mesh& m = scene.meshes[0];
    ASSERT_EQ(m.faces.size(), 2u) << type;
    EXPECT_EQ(m.faces[1], (std::array<std::uint32_t, 3>{0, 2, 3})) << type;
  }
}

// glTF 2.0 3.7.2.1: strip triangle i is (p_i, p_i+1, p_i+2), every odd one turned to keep
// the winding; fan triangle i is (p_0, p_i+1, p_i+2).
TEST(Gltf, TriangleStripsAndFansBecomeTrianglesInTheirWinding) {
  using Face = std::array<std::uint32_t, 3>;
  for (const int mode : {5, 6}) {
    const test::TempDir dir("gltf");
    GltfFile f;
    f.floats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 2, 0}, "VEC3", 3);
    const std::string rest = R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0},"mode":)" +
                             std::to_string(mode) + "}]}]";
    const Scene scene = load_scene(dir.write("strip.gltf", f.json(rest)));
    const std::vector<Face> want = mode == 5 ? std::vector<Face>{{0, 1, 2}, {2, 1, 3}, {2, 3, 4}}
                                             : std::vector<Face>{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}};
    EXPECT_EQ(scene.meshes.at(0).faces, want) << "mode " << mode;
  }
}

TEST(Gltf, MaterialFactorsMapToPbrFields) {
  const test::TempDir dir("gltf");
  const std::string rest =
      R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0},"material":0}]}],)"
      R"("materials":[{"name":"shiny","pbrMetallicRoughness":{"baseColorFactor":[0.5,0.25,1,0.5],)"
      R"("metallicFactor":0.3,"roughnessFactor":0.7},"emissiveFactor":[1,0,0],)"
      R"("extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":2},)"
      R"("KHR_materials_transmission":{"transmissionFactor":0.4},"KHR_materials_ior":{"ior":1.33}}}])";
  const Scene scene = load_scene(dir.write("mat.gltf", triangle().json(rest)));
  const int i = scene.find_material("mat.gltf:shiny");
  ASSERT_GE(i, 0);
  const Material& m = scene.materials[std::size_t(i)];
  EXPECT_EQ(m.model, Shading::pbr);
  expect_near(m.base_color, 0.5f, 0.25f, 1.0f);
  EXPECT_FLOAT_EQ(m.metallic, 0.3f);
  EXPECT_FLOAT_EQ(m.roughness, 0.7f);
  expect_near(m.emissive, 2, 0, 0);
  EXPECT_FLOAT_EQ(m.transmission, 0.4f);
  EXPECT_FLOAT_EQ(m.ior, 1.33f);
  EXPECT_EQ(scene.meshes.at(0).face_materials.at(0), std::uint32_t(i));
}

TEST(Gltf, DefaultMaterialIsTheSpecsDefault) {
  const test::TempDir dir("gltf");
  const Scene scene = load_scene(dir.write("d.gltf", triangle().json(kTriangleMesh)));
  const int i = scene.find_material("d.gltf:default");
  ASSERT_GE(i, 0);
  const Material& m = scene.materials[std::size_t(i)];
  EXPECT_EQ(m.model, Shading::pbr);
  EXPECT_FLOAT_EQ(m.metallic, 1.0f);
  EXPECT_FLOAT_EQ(m.roughness, 1.0f);
  expect_near(m.base_color, 1, 1, 1);
}

TEST(Gltf, TexturesGetTheirColourSpaceAndAreSharedPerImageAndSpace) {
  const test::TempDir dir("gltf");
  dir.write("tex.png", "not decoded at load");
  const std::string rest =
      R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":2},"material":0}]}],)"
      R"("images":[{"uri":"tex.png"},{"uri":"data:image/png;base64,AAECAw=="}],)"
      R"("textures":[{"source":0},{"source":1}],)"
      R"("materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0},)"
      R"("metallicRoughnessTexture":{"index":0}},"normalTexture":{"index":0,"scale":0.5},)"
      R"("emissiveTexture":{"index":1}}])";
  const Scene scene = load_scene(dir.write("tex.gltf", triangle().json(rest)));
  const Material& m = scene.materials.at(std::size_t(scene.find_material("tex.gltf:#0")));
  ASSERT_EQ(scene.textures.size(), 3u);
  const TextureDesc& base = scene.textures.at(m.base_color_texture);
  EXPECT_TRUE(base.srgb);
  EXPECT_EQ(fs::path(base.path).filename(), "tex.png");
  EXPECT_TRUE(base.data.empty());
  EXPECT_EQ(m.metallic_roughness_texture, m.normal_texture);
  EXPECT_NE(m.metallic_roughness_texture, m.base_color_texture);
  EXPECT_FALSE(scene.textures.at(m.normal_texture).srgb);
  EXPECT_FLOAT_EQ(m.normal_scale, 0.5f);
  const TextureDesc& emissive = scene.textures.at(m.emissive_texture);
  EXPECT_TRUE(emissive.srgb);
  EXPECT_EQ(emissive.path, "tex.gltf:image 1");
  EXPECT_EQ(emissive.data, std::string("\x00\x01\x02\x03", 4));
}

TEST(Gltf, MissingImageFileIsOneLine) {
  const test::TempDir dir("gltf");
  const std::string rest =
      R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0},"material":0}]}],)"
      R"("images":[{"uri":"missing.png"}],"textures":[{"source":0}],)"
      R"("materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}])";
  const std::string path = dir.write("m.gltf", triangle().json(rest));
  EXPECT_EQ(test::error_of([&] { load_scene(path); }),
            path + ": image 0: missing.png: No such file or directory");
}

TEST(Gltf, CameraComesFromItsNode) {
  const test::TempDir dir("gltf");
  const std::string rest =
      kTriangleMesh +
      R"(,"cameras":[{"type":"perspective","perspective":{"yfov":0.5,"znear":0.1}}],)"
      R"("nodes":[{"mesh":0},{"camera":0,"translation":[0,1,5]}],"scenes":[{"nodes":[0,1]}])";
  const Scene scene = load_scene(dir.write("cam.gltf", triangle().json(rest)));
  expect_near(scene.camera.position(), 0, 1, 5);
  expect_near(scene.camera.forward(), 0, 0, -1);
  expect_near(scene.camera.up(), 0, 1, 0);
  EXPECT_NEAR(scene.camera.fov(), 0.5f * 180.0f / 3.14159265f, 1e-3f);
}

TEST(Gltf, SceneWithoutCameraOrLightsIsFramed) {
  const test::TempDir dir("gltf");
  const Scene scene = load_scene(dir.write("framed.gltf", triangle().json(kTriangleMesh)));
  // In front of the triangle (+z) and above it, looking at its centre, and fitted to the
  // image later (framed_bounds), as a bare OBJ.
  EXPECT_GT(scene.camera.position()[2], 1.0f);
  EXPECT_GT(scene.camera.position()[1], 0.5f);
  const vec4 to_centre = normalize(vec4(0.5f, 0.5f, 0.0f) - scene.camera.position());
  EXPECT_GT(float(dot(to_centre, scene.camera.forward())), 0.9999f);
  EXPECT_TRUE(scene.framed_bounds.has_value());
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_GT(scene.lights[0].position[1], 1.0f);
}

TEST(Gltf, PointLightGivesItsIlluminanceAtTheSceneCentre) {
  const test::TempDir dir("gltf");
  const std::string rest =
      kTriangleMesh +
      R"(,"extensionsUsed":["KHR_lights_punctual"],)"
      R"("extensions":{"KHR_lights_punctual":{"lights":[{"type":"point","intensity":100,)"
      R"("color":[1,0.5,0.25],"range":50}]}},)"
      R"("nodes":[{"mesh":0},{"translation":[0.5,0.5,10],)"
      R"("extensions":{"KHR_lights_punctual":{"light":0}}}],"scenes":[{"nodes":[0,1]}])";
  const Scene scene = load_scene(dir.write("light.gltf", triangle().json(rest)));
  ASSERT_EQ(scene.lights.size(), 1u);
  const Light& l = scene.lights[0];
  expect_near(l.position, 0.5f, 0.5f, 10);
  expect_near(l.color, 1, 0.5f, 0.25f);
  EXPECT_NEAR(l.intensity, 100.0f / 100.0f, 1e-4f);  // 100 cd at 10 units from the centre
  EXPECT_FLOAT_EQ(l.range, 50.0f);
}

TEST(Gltf, GlbLoadsAsItsJsonForm) {
  const test::TempDir dir("gltf");
  const std::string nodes =
      R"(,"nodes":[{"mesh":0,"translation":[1,2,3]}],"scenes":[{"nodes":[0]}])";
  const GltfFile f = triangle();
  const Scene a = load_scene(dir.write("a.gltf", f.json(kTriangleMesh + nodes)));
  const Scene b = load_scene(dir.write("b.GLB", f.glb(kTriangleMesh + nodes)));
  ASSERT_EQ(b.meshes.size(), 1u);
  ASSERT_EQ(a.meshes[0].positions.size(), b.meshes[0].positions.size());
  for (std::size_t i = 0; i < a.meshes[0].positions.size(); ++i)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(a.meshes[0].positions[i][k], b.meshes[0].positions[i][k]);
  expect_near(b.meshes[0].positions[1], 2, 2, 3);
}

TEST(Gltf, NodeCycleIsAnError) {
  const test::TempDir dir("gltf");
  const std::string rest =
      kTriangleMesh +
      R"(,"nodes":[{"mesh":0,"children":[1]},{"children":[0]}],"scenes":[{"nodes":[0]}])";
  const std::string path = dir.write("cycle.gltf", triangle().json(rest));
  const std::string msg = test::error_of([&] { load_scene(path); });
  EXPECT_EQ(msg.rfind(path + ": node #0 is its own descendant", 0), 0u) << msg;
}

// Every glTF 2.0 file of Debian's assimp-testmodels: loads (and validates) or fails with a
// one-line rt2::Error naming the file; nothing else escapes.
TEST(Gltf, AssimpTestModelsLoadOrFailWithOneLine) {
  const fs::path root = "/usr/share/assimp/models/glTF2";
  std::error_code ec;
  if (!fs::is_directory(root, ec)) GTEST_SKIP() << "assimp-testmodels is not installed";
  int loaded = 0, refused = 0;
  for (const auto& e : fs::recursive_directory_iterator(root, ec)) {
    const std::string ext = e.path().extension().string();
    if (ext != ".gltf" && ext != ".glb") continue;
    const std::string path = e.path().string();
    testing::internal::CaptureStderr();
    try {
      const Scene scene = load_scene(path);
      EXPECT_NO_THROW(scene.validate()) << path;
      ++loaded;
    } catch (const Error& err) {
      const std::string msg = err.what();
      EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
      EXPECT_EQ(msg.rfind(path + ": ", 0), 0u) << msg;
      ++refused;
    } catch (const std::exception& err) {
      ADD_FAILURE() << path << ": threw something other than rt2::Error: " << err.what();
    }
    testing::internal::GetCapturedStderr();
  }
  EXPECT_GE(loaded, 20) << "refused " << refused;
  std::cout << "assimp-testmodels glTF2: " << loaded << " loaded, " << refused << " refused\n";
}

}  // namespace
}  // namespace rt2
