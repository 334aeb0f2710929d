// tests/rt2/io/gltf_extensions_test.cpp — glTF as the everyday tools write it, and glTF that
// must not get through: quantized attributes, meshopt and Draco compression (encoded here
// with Debian's meshoptimizer and draco, decoded by rt2, compared with the plain file),
// texture transforms, specular-glossiness, extensionsRequired and extensionsUsed, glTF 1.0,
// JSON bombs, schema violations named by their JSON path, and files outside the asset's
// folder.
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <gtest/gtest.h>
#include <meshoptimizer.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
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

// A small closed mesh: an octahedron of 6 vertices and 8 triangles, with normals and texture
// coordinates, as floats.
struct Octahedron {
  std::vector<float> positions = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
  std::vector<float> normals = positions;
  std::vector<float> uvs = {0, 0, 1, 0, 0.25f, 0.5f, 0.75f, 0.5f, 0.5f, 0.125f, 0.5f, 0.875f};
  std::vector<std::uint16_t> indices = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4,
                                        2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
};

const std::string kMesh =
    R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2},)"
    R"("indices":3}]}])";
const std::string kMeshWithMaterial =
    R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2},)"
    R"("indices":3,"material":0}]}])";

// The octahedron as a plain glTF (float attributes, 16-bit indices), its primitive of
// material 0 when `rest` defines materials.
std::string plain_octahedron(const std::string& rest = "") {
  const Octahedron o;
  GltfFile f;
  f.floats(o.positions, "VEC3", 3);
  f.floats(o.normals, "VEC3", 3);
  f.floats(o.uvs, "VEC2", 2);
  f.accessor(o.indices, 5123, "SCALAR", o.indices.size());
  const bool material = rest.find("\"materials\"") != std::string::npos;
  return f.json((material ? kMeshWithMaterial : kMesh) + rest);
}

// Each triangle of the scene's meshes as its three corner positions, sorted, so that two
// meshes with the same triangles in another vertex order compare equal.
std::vector<std::array<float, 9>> triangles(const Scene& s) {
  std::vector<std::array<float, 9>> out;
  for (const Mesh& m : s.meshes)
    for (const auto& f : m.faces) {
      std::array<std::array<float, 3>, 3> c;
      for (int k = 0; k < 3; ++k)
        for (int a = 0; a < 3; ++a)
          c[std::size_t(k)][std::size_t(a)] = m.positions[f[std::size_t(k)]][a];
      std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());  // keep the winding
      out.push_back(
          {c[0][0], c[0][1], c[0][2], c[1][0], c[1][1], c[1][2], c[2][0], c[2][1], c[2][2]});
    }
  std::sort(out.begin(), out.end());
  return out;
}

void expect_same_triangles(const Scene& a, const Scene& b, float eps) {
  const auto ta = triangles(a), tb = triangles(b);
  ASSERT_EQ(ta.size(), tb.size());
  for (std::size_t i = 0; i < ta.size(); ++i)
    for (int k = 0; k < 9; ++k) EXPECT_NEAR(ta[i][std::size_t(k)], tb[i][std::size_t(k)], eps) << i;
}

TEST(GltfQuantization, IntegerAttributesDecodeAsTheSpecNormalizesThem) {
  const test::TempDir dir("gltfq");
  GltfFile f;
  // Positions: normalized shorts (32767 = 1, -32768 clamps to -1) scaled 2x by the node;
  // normals: normalized bytes; texture coordinates: unnormalized unsigned shorts, which
  // KHR_mesh_quantization allows and a texture transform (scale 1/1024) maps to [0, 1].
  f.accessor(std::vector<std::int16_t>{32767, 0, 0, 0, 32767, 0, -32768, -32768, 0, 0}, 5122,
             "VEC3", 3, true);
  f.accessor(std::vector<std::int8_t>{0, 0, 127, 0, 0, 127, 0, 0, -128, 0, 0, 0}, 5120, "VEC3", 3,
             true);
  f.accessor(std::vector<std::uint16_t>{0, 0, 1024, 0, 512, 256}, 5123, "VEC2", 3);
  const std::string rest =
      R"(,"extensionsUsed":["KHR_mesh_quantization","KHR_texture_transform"],)"
      R"("extensionsRequired":["KHR_mesh_quantization"],)"
      R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2},)"
      R"("material":0}]}],"materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0,)"
      R"("extensions":{"KHR_texture_transform":{"scale":[0.0009765625,0.0009765625]}}}}}],)"
      R"("textures":[{"source":0}],"images":[{"uri":"t.png"}],)"
      R"("nodes":[{"mesh":0,"scale":[2,2,2]}],"scenes":[{"nodes":[0]}])";
  dir.write("t.png", "not decoded at load");
  const Scene s = load_scene(dir.write("q.gltf", f.json(rest)));
  ASSERT_EQ(s.meshes.size(), 1u);
  const Mesh& m = s.meshes[0];
  ASSERT_EQ(m.positions.size(), 3u);
  EXPECT_FLOAT_EQ(m.positions[0][0], 2.0f);
  EXPECT_FLOAT_EQ(m.positions[1][1], 2.0f);
  EXPECT_FLOAT_EQ(m.positions[2][0], -2.0f);  // -32768 / 32767 clamps to -1
  ASSERT_EQ(m.normals.size(), 3u);
  EXPECT_FLOAT_EQ(m.normals[0][2], 1.0f);
  EXPECT_FLOAT_EQ(m.normals[2][2], -1.0f);  // -128 / 127 clamps to -1
  ASSERT_EQ(m.texcoords.size(), 3u);
  EXPECT_FLOAT_EQ(m.texcoords[1][0], 1.0f);
  EXPECT_FLOAT_EQ(m.texcoords[2][0], 0.5f);
  EXPECT_FLOAT_EQ(m.texcoords[2][1], 0.75f);  // rt2's v = 1 - glTF's 0.25
}

TEST(GltfQuantization, UnnormalizedIntegerNormalsAreAnError) {
  const test::TempDir dir("gltfq");
  GltfFile f;
  f.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  f.accessor(std::vector<std::int8_t>{0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0}, 5120, "VEC3", 3);
  const std::string path = dir.write(
      "n.gltf", f.json(R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1}}]}])"));
  EXPECT_NE(test::error_of([&] { load_scene(path); }).find("integer normals must be normalized"),
            std::string::npos);
}

// The octahedron with its attributes and indices in meshopt-compressed buffer views of buffer
// 0, and buffer 1 a fallback that holds no data, as gltfpack -c writes it.
std::string meshopt_octahedron(bool glb) {
  const Octahedron o;
  std::vector<float> vertices;  // interleaved: position, normal, uv (32 bytes)
  for (std::size_t i = 0; i < 6; ++i) {
    for (int a = 0; a < 3; ++a) vertices.push_back(o.positions[3 * i + std::size_t(a)]);
    for (int a = 0; a < 3; ++a) vertices.push_back(o.normals[3 * i + std::size_t(a)]);
    for (int a = 0; a < 2; ++a) vertices.push_back(o.uvs[2 * i + std::size_t(a)]);
  }
  std::string vbuf(meshopt_encodeVertexBufferBound(6, 32), '\0');
  vbuf.resize(meshopt_encodeVertexBuffer(reinterpret_cast<unsigned char*>(vbuf.data()), vbuf.size(),
                                         vertices.data(), 6, 32));
  std::vector<unsigned int> idx(o.indices.begin(), o.indices.end());
  std::string ibuf(meshopt_encodeIndexBufferBound(idx.size(), 6), '\0');
  ibuf.resize(meshopt_encodeIndexBuffer(reinterpret_cast<unsigned char*>(ibuf.data()), ibuf.size(),
                                        idx.data(), idx.size()));
  GltfFile f;
  const std::size_t v_at = f.append(vbuf), i_at = f.append(ibuf);
  const std::string views =
      R"([{"buffer":1,"byteOffset":0,"byteLength":192,"byteStride":32,"extensions":)"
      R"({"EXT_meshopt_compression":{"buffer":0,"byteOffset":)" +
      std::to_string(v_at) + R"(,"byteLength":)" + std::to_string(vbuf.size()) +
      R"(,"byteStride":32,"mode":"ATTRIBUTES","count":6}}},)"
      R"({"buffer":1,"byteOffset":192,"byteLength":48,"extensions":{"EXT_meshopt_compression":)"
      R"({"buffer":0,"byteOffset":)" +
      std::to_string(i_at) + R"(,"byteLength":)" + std::to_string(ibuf.size()) +
      R"(,"byteStride":2,"mode":"TRIANGLES","count":24}}}])";
  const std::string accessors =
      R"([{"bufferView":0,"byteOffset":0,"componentType":5126,"count":6,"type":"VEC3"},)"
      R"({"bufferView":0,"byteOffset":12,"componentType":5126,"count":6,"type":"VEC3"},)"
      R"({"bufferView":0,"byteOffset":24,"componentType":5126,"count":6,"type":"VEC2"},)"
      R"({"bufferView":1,"componentType":5123,"count":24,"type":"SCALAR"}])";
  const std::string bin = f.bin();
  std::string json =
      R"({"asset":{"version":"2.0"},"extensionsUsed":["EXT_meshopt_compression"],)"
      R"("extensionsRequired":["EXT_meshopt_compression"],"buffers":[{"byteLength":)" +
      std::to_string(bin.size()) +
      (glb ? "" : R"(,"uri":"data:application/octet-stream;base64,)" + test::base64(bin) + "\"") +
      R"(},{"byteLength":240,"extensions":{"EXT_meshopt_compression":{"fallback":true}}}],)"
      R"("bufferViews":)" +
      views + R"(,"accessors":)" + accessors + kMesh +
      R"(,"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}]})";
  return glb ? test::glb_of(json, bin) : json;
}

TEST(GltfMeshopt, CompressedBuffersDecodeToTheUncompressedData) {
  const test::TempDir dir("gltfm");
  const Scene plain = load_scene(dir.write("plain.gltf", plain_octahedron()));
  for (const bool glb : {false, true}) {
    const Scene packed = load_scene(dir.write(glb ? "m.glb" : "m.gltf", meshopt_octahedron(glb)));
    expect_same_triangles(plain, packed, 0.0f);
    ASSERT_EQ(packed.meshes.size(), 1u);
    EXPECT_EQ(packed.meshes[0].normals.size(), 6u);
    EXPECT_EQ(packed.meshes[0].texcoords.size(), 6u);
  }
}

TEST(GltfMeshopt, CorruptCompressedDataIsOneLine) {
  const test::TempDir dir("gltfm");
  std::string json = meshopt_octahedron(false);
  // Garble the compressed bytes: the base64 payload's middle.
  const std::size_t at = json.find("base64,") + 20;
  for (std::size_t i = at; i < at + 40; ++i) json[i] = 'A';
  const std::string path = dir.write("bad.gltf", json);
  const std::string msg = test::error_of([&] { load_scene(path); });
  EXPECT_EQ(msg.rfind(path + ": ", 0), 0u) << msg;
  EXPECT_NE(msg.find("EXT_meshopt_compression"), std::string::npos) << msg;
}

TEST(GltfMeshopt, AViewOfAFallbackBufferWithoutCompressionIsAnError) {
  const test::TempDir dir("gltfm");
  std::string json = meshopt_octahedron(false);
  // The index view loses its extension and so reads the fallback buffer itself.
  const std::size_t from = json.find(R"("byteLength":48,"extensions")");
  const std::size_t to = json.find("}}}]", from);
  json = json.substr(0, from) + R"("byteLength":48}])" + json.substr(to + 4);
  const std::string path = dir.write("fallback.gltf", json);
  EXPECT_NE(test::error_of([&] { load_scene(path); }).find("fallback buffer"), std::string::npos);
}

// The octahedron Draco-compressed (positions quantized to 14 bits), as gltf-pipeline -d
// writes it: the primitive's accessors have no bufferView.
std::string draco_octahedron() {
  const Octahedron o;
  draco::TriangleSoupMeshBuilder builder;
  builder.Start(8);
  const int pos = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  for (int t = 0; t < 8; ++t) {
    const auto corner = [&](int k) {
      return o.positions.data() + 3 * o.indices[std::size_t(3 * t + k)];
    };
    builder.SetAttributeValuesForFace(pos, draco::FaceIndex(std::uint32_t(t)), corner(0), corner(1),
                                      corner(2));
  }
  const std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
  draco::EncoderBuffer out;
  EXPECT_TRUE(encoder.EncodeMeshToBuffer(*mesh, &out).ok());
  const std::string bytes(out.data(), out.size());
  GltfFile f;
  f.append(bytes);
  const int id = mesh->attribute(0)->unique_id();
  return R"({"asset":{"version":"2.0"},"extensionsUsed":["KHR_draco_mesh_compression"],)"
         R"("extensionsRequired":["KHR_draco_mesh_compression"],)"
         R"("buffers":[{"byteLength":)" +
         std::to_string(f.bin().size()) + R"(,"uri":"data:application/octet-stream;base64,)" +
         test::base64(f.bin()) +
         R"("}],)"
         R"("bufferViews":[{"buffer":0,"byteLength":)" +
         std::to_string(bytes.size()) +
         R"(}],)"
         R"("accessors":[{"componentType":5126,"count":)" +
         std::to_string(mesh->num_points()) +
         R"(,"type":"VEC3","min":[-1,-1,-1],"max":[1,1,1]},)"
         R"({"componentType":5125,"count":24,"type":"SCALAR"}],)"
         R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1,)"
         R"("extensions":{"KHR_draco_mesh_compression":{"bufferView":0,"attributes":{"POSITION":)" +
         std::to_string(id) + R"(}}}}]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}]})";
}

TEST(GltfDraco, CompressedPrimitivesDecodeToTheirTriangles) {
  const test::TempDir dir("gltfd");
  const Scene plain = load_scene(dir.write("plain.gltf", plain_octahedron()));
  const Scene packed = load_scene(dir.write("d.gltf", draco_octahedron()));
  // 14-bit quantization over an extent of 2: a step of 2 / 16383.
  expect_same_triangles(plain, packed, 2.0f / 16383.0f);
}

TEST(GltfDraco, MalformedCompressedDataIsOneLine) {
  const test::TempDir dir("gltfd");
  std::string json = draco_octahedron();
  const std::size_t at = json.find("base64,") + 12;
  for (std::size_t i = at; i < at + 24; ++i) json[i] = 'Z';
  const std::string path = dir.write("bad.gltf", json);
  const std::string msg = test::error_of([&] { load_scene(path); });
  EXPECT_EQ(msg.rfind(path + ": ", 0), 0u) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
}

TEST(GltfTextureTransform, OffsetRotationAndScaleApplyToTheTextureCoordinates) {
  const test::TempDir dir("gltft");
  dir.write("t.png", "not decoded at load");
  GltfFile f;
  f.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  f.floats({0, 0, 1, 0, 0, 1}, "VEC2", 2);
  // Scale 2, then a quarter turn (u' = cos u + sin v, v' = -sin u + cos v), then offset
  // (0.5, 0.25): (1, 0) -> (2, 0) -> (0, -2) -> (0.5, -1.75); (0, 1) -> (0, 2) -> (2, 0) ->
  // (2.5, 0.25).
  const std::string rest =
      R"(,"extensionsUsed":["KHR_texture_transform"],)"
      R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1},"material":0}]}],)"
      R"("materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0,"extensions":)"
      R"({"KHR_texture_transform":{"offset":[0.5,0.25],"rotation":1.5707963267948966,)"
      R"("scale":[2,2]}}}}}],"textures":[{"source":0}],"images":[{"uri":"t.png"}])";
  const Scene s = load_scene(dir.write("t.gltf", f.json(rest)));
  const auto& uv = s.meshes.at(0).texcoords;
  ASSERT_EQ(uv.size(), 3u);
  EXPECT_NEAR(uv[0][0], 0.5f, 1e-6f);
  EXPECT_NEAR(uv[0][1], 1.0f - 0.25f, 1e-6f);
  EXPECT_NEAR(uv[1][0], 0.5f, 1e-6f);
  EXPECT_NEAR(uv[1][1], 1.0f + 1.75f, 1e-6f);
  EXPECT_NEAR(uv[2][0], 2.5f, 1e-6f);
  EXPECT_NEAR(uv[2][1], 1.0f - 0.25f, 1e-6f);
}

TEST(GltfSpecularGlossiness, ConvertsToMetallicRoughness) {
  const test::TempDir dir("gltfs");
  const auto material = [&](const std::string& ext) {
    const std::string rest =
        R"(,"extensionsUsed":["KHR_materials_pbrSpecularGlossiness"],"materials":[{"extensions":)"
        R"({"KHR_materials_pbrSpecularGlossiness":)" +
        ext + "}}]";
    const Scene s = load_scene(dir.write("s.gltf", plain_octahedron(rest)));
    return s.materials.at(std::size_t(s.find_material("s.gltf:#0")));
  };
  // A dielectric: 4 % specular reflects as a non-metal; its base colour is its diffuse.
  const Material plastic = material(
      R"({"diffuseFactor":[0.5,0.25,0.125,1],"specularFactor":[0.04,0.04,0.04],)"
      R"("glossinessFactor":0.7})");
  EXPECT_FLOAT_EQ(plastic.metallic, 0.0f);
  EXPECT_NEAR(plastic.roughness, 0.3f, 1e-6f);
  EXPECT_NEAR(plastic.base_color[0], 0.5f, 1e-6f);
  EXPECT_NEAR(plastic.base_color[2], 0.125f, 1e-6f);
  // A metal: black diffuse, coloured specular: metallic 1, base colour the specular colour.
  const Material gold = material(
      R"({"diffuseFactor":[0,0,0,1],"specularFactor":[1,0.766,0.336],"glossinessFactor":1})");
  EXPECT_FLOAT_EQ(gold.metallic, 1.0f);
  EXPECT_FLOAT_EQ(gold.roughness, 0.0f);
  EXPECT_NEAR(gold.base_color[1], 0.766f, 1e-6f);
}

TEST(GltfExtensions, ARequiredExtensionRt2LacksIsRefusedByName) {
  const test::TempDir dir("gltfe");
  const std::string path =
      dir.write("r.gltf", plain_octahedron(R"(,"extensionsUsed":["KHR_texture_basisu"],)"
                                           R"("extensionsRequired":["KHR_texture_basisu"])"));
  EXPECT_EQ(test::error_of([&] { load_scene(path); }),
            path +
                ": requires extension KHR_texture_basisu (extensionsRequired), which rt2 "
                "does not implement");
}

TEST(GltfExtensions, AUsedExtensionRt2IgnoresIsWarnedByName) {
  const test::TempDir dir("gltfe");
  const std::string path = dir.write(
      "u.gltf", plain_octahedron(R"(,"extensionsUsed":["KHR_materials_clearcoat","VENDOR_x"])"));
  testing::internal::CaptureStderr();
  load_scene(path);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("ignores extension KHR_materials_clearcoat: clearcoat layers are not drawn"),
            std::string::npos)
      << err;
  EXPECT_NE(err.find("ignores extension VENDOR_x"), std::string::npos) << err;
}

TEST(GltfExtensions, MorphTargetsAreAppliedWithoutAWord) {
  const test::TempDir dir("gltfe");
  GltfFile f;
  f.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  f.floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
  const std::string path =
      dir.write("morph.gltf", f.json(R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0},)"
                                     R"("targets":[{"POSITION":1}]}],"weights":[0.5]}])"));
  testing::internal::CaptureStderr();
  const Scene s = load_scene(path);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  ASSERT_EQ(s.meshes.size(), 1u);
  for (const vec4& p : s.meshes[0].positions) EXPECT_EQ(p[2], 0.5f);  // base + 0.5 x (0, 0, 1)
}

TEST(GltfVersion, Gltf1IsRefusedWithItsVersion) {
  const test::TempDir dir("gltfv");
  const std::string v1 =
      dir.write("v1.gltf", R"({"asset":{"version":"1.0"},"meshes":{"m":{"primitives":[]}}})");
  EXPECT_EQ(test::error_of([&] { load_scene(v1); }),
            v1 + ": glTF 1.0 is not supported (asset.version '1.0'); rt2 reads glTF 2.0 (convert "
                 "it, e.g. with Khronos' glTF-Pipeline)");
  const std::string keyed = dir.write("keyed.gltf", R"({"meshes":{"m":{"primitives":[]}}})");
  EXPECT_NE(test::error_of([&] { load_scene(keyed); }).find("glTF 1.0 is not supported"),
            std::string::npos);
  std::string glb1 = test::glb_of(R"({"asset":{"version":"1.0"}})", "");
  glb1[4] = 1;  // header version 1: binary glTF 1.0
  const std::string b1 = dir.write("v1.glb", glb1);
  EXPECT_NE(test::error_of([&] { load_scene(b1); }).find("glTF 1.0 is not supported"),
            std::string::npos);
}

TEST(GltfBombs, DeeplyNestedJsonIsRefusedBeforeItIsParsed) {
  const test::TempDir dir("gltfb");
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  for (const std::string& json :
       {R"({"asset":{"version":"2.0"},"extras":)" + deep + "}", std::string(100000, '{')}) {
    const std::string path = dir.write("deep.gltf", json);
    EXPECT_NE(test::error_of([&] {
                load_scene(path);
              }).find("JSON nests arrays and objects more than 128 deep"),
              std::string::npos);
  }
}

TEST(GltfBombs, ALightInstancedByANodeGraphIsBounded) {
  const test::TempDir dir("gltfb");
  // Two nodes per level, each a parent of both nodes of the next level: 2^13 paths reach
  // the lights of the last level.
  std::string nodes = R"(,"nodes":[{"mesh":0,"children":[1,2]})";
  for (int level = 0; level < 12; ++level) {
    const std::string next = std::to_string(3 + 2 * level) + "," + std::to_string(4 + 2 * level);
    nodes += R"(,{"children":[)" + next + R"(]},{"children":[)" + next + "]}";
  }
  nodes += R"(,{"extensions":{"KHR_lights_punctual":{"light":0}}},)"
           R"({"extensions":{"KHR_lights_punctual":{"light":0}}}],"scenes":[{"nodes":[0]}],)"
           R"("extensionsUsed":["KHR_lights_punctual"],)"
           R"("extensions":{"KHR_lights_punctual":{"lights":[{"type":"point"}]}})";
  const std::string path = dir.write("lights.gltf", plain_octahedron(nodes));
  EXPECT_NE(test::error_of([&] { load_scene(path); }).find("more than 4096 light instances"),
            std::string::npos);
}

// Each schema violation is an error that names the JSON path, never a default.
TEST(GltfSchema, ViolationsNameTheirJsonPath) {
  const test::TempDir dir("gltfs");
  struct Case {
    std::string from, to, message;
  };
  const std::string base = plain_octahedron(R"(,"materials":[{"name":"m"}])");
  const std::vector<Case> cases = {
      {R"("materials":[{"name":"m"}])",
       R"("materials":[{"pbrMetallicRoughness":{"baseColorFactor":[1,1,1,1,1]}}])",
       "materials[0].pbrMetallicRoughness.baseColorFactor has 5 elements, expected 4"},
      {R"("materials":[{"name":"m"}])", R"("materials":[{"pbrMetallicRoughness":["x"]}])",
       "materials[0].pbrMetallicRoughness is an array, expected an object"},
      {R"("materials":[{"name":"m"}])", R"("materials":[{"emissiveFactor":[2,0,0]}])",
       "materials[0].emissiveFactor[0] is 2, expected 0 to 1"},
      {R"("scenes":[{"nodes":[0]}])", R"("scenes":[{"nodes":[0],"name":42}])",
       "scenes[0].name is a number, expected a string"},
      {R"("byteOffset":0,)", R"("byteOffset":-4,)",
       "bufferViews[0].byteOffset is -4, expected >= 0"},
      {R"("buffer":0,"byteOffset":0,)", R"("buffer":0,"byteStride":-12,"byteOffset":0,)",
       "bufferViews[0].byteStride is -12, expected 4 to 252"},
      {R"("componentType":5126)", R"("componentType":5130)",
       "accessors[0].componentType is 5130, expected one of"},
      {R"("nodes":[{"mesh":0}])", R"("nodes":[{"mesh":0.5}])",
       "nodes[0].mesh is not a whole number"},
      {R"("nodes":[{"mesh":0}])", R"("nodes":[{"mesh":0,"rotation":[0,0,0]}])",
       "nodes[0].rotation has 3 elements, expected 4"},
  };
  for (const Case& c : cases) {
    std::string json = base;
    const std::size_t at = json.find(c.from);
    ASSERT_NE(at, std::string::npos) << c.from;
    json.replace(at, c.from.size(), c.to);
    const std::string path = dir.write("s.gltf", json);
    const std::string msg = test::error_of([&] { load_scene(path); });
    EXPECT_EQ(msg.rfind(path + ": " + c.message, 0), 0u) << msg;
  }
}

TEST(GltfSchema, OnlyTheFirstGlbBufferMayUseTheBinChunk) {
  const test::TempDir dir("gltfs");
  const std::string json =
      R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":4},{"byteLength":4}]})";
  const std::string path = dir.write("two.glb", test::glb_of(json, std::string(4, '\0')));
  EXPECT_EQ(test::error_of([&] { load_scene(path); }),
            path + ": buffers[1] has no uri: only the first buffer of a GLB may use its BIN chunk");
}

// Files an asset names stay in its folder: `..`, absolute paths, symbolic links and URI
// schemes are refused by name unless the policy allows them.
TEST(GltfConfinement, FilesOutsideTheAssetsFolderAreRefusedUnlessAllowed) {
  const test::TempDir dir("gltfc");
  fs::create_directories(dir.root() / "asset");
  fs::create_directories(dir.root() / "outside");
  dir.write("outside/secret.png", "secret");
  fs::create_symlink(dir.root() / "outside", dir.root() / "asset" / "link");
  const auto with_image = [&](const std::string& uri) {
    return plain_octahedron(
        R"(,"materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],)"
        R"("textures":[{"source":0}],"images":[{"uri":")" +
        uri + R"("}])");
  };
  const std::string absolute = (dir.root() / "outside" / "secret.png").string();
  for (const std::string& uri :
       {std::string("../outside/secret.png"), absolute, std::string("link/secret.png"),
        std::string("%2E%2E/outside/secret.png")}) {
    const std::string path = dir.write("asset/x.gltf", with_image(uri));
    const std::string msg = test::error_of([&] { load_scene(path); });
    EXPECT_NE(msg.find("lies outside the folder of x.gltf"), std::string::npos)
        << uri << ": " << msg;
    AssetPolicy allow;
    allow.allow_outside_assets = true;
    const Scene s = load_scene(path, allow);
    ASSERT_EQ(s.textures.size(), 1u) << uri;
  }
  const std::string web = dir.write("asset/web.gltf", with_image("https://example.com/a.png"));
  EXPECT_NE(test::error_of([&] { load_scene(web); }).find("is a URI with scheme 'https'"),
            std::string::npos);
  // A buffer climbing out to a system file.
  std::string json = plain_octahedron();
  const std::size_t uri = json.find(R"("uri":"data:)");
  json = json.substr(0, uri) + R"("uri":"../../../../../../../../etc/passwd"})" +
         json.substr(json.find("\"}", uri) + 2);
  const std::string bad_buffer = dir.write("asset/buffer.gltf", json);
  EXPECT_NE(test::error_of([&] { load_scene(bad_buffer); }).find("buffers[0].uri: '../../"),
            std::string::npos);
}

// Compressed and quantized files render as their uncompressed originals: PSNR >= 30 dB at
// 160 x 120, for the files encoded here and for those the tools wrote (tests/hostile/tools_*).
TEST(GltfRender, CompressedFilesRenderAsTheirOriginals) {
  const test::TempDir dir("gltfr");
  RenderSettings st;
  st.width = 160;
  st.height = 120;
  st.depth = 2;
  const auto render = [&](const std::string& path) {
    Scene s = load_scene(path);
    fit_framed_camera(s, st.width, st.height);
    return test::render_scene(s, st);
  };
  const auto expect_close = [&](const Image& image, const Image& reference,
                                const std::string& what) {
    const ImageError e = compare_images(image, reference);
    std::printf("[ measure  ] %s: PSNR %.1f dB\n", what.c_str(), e.psnr);
    EXPECT_GE(e.psnr, 30.0) << what;
  };
  const Image plain = render(dir.write("plain.gltf", plain_octahedron()));
  expect_close(render(dir.write("m.glb", meshopt_octahedron(true))), plain, "meshopt");
  expect_close(render(dir.write("d.gltf", draco_octahedron())), plain, "Draco");
  const std::string hostile = std::string(RT2_SOURCE_DIR) + "/tests/hostile/";
  const Image tetra = render(hostile + "tools_obj2gltf.glb");
  for (const char* f :
       {"tools_gltfpack.glb", "tools_gltfpack_meshopt.glb", "tools_gltf_pipeline_draco.glb"})
    expect_close(render(hostile + f), tetra, f);
}

}  // namespace
}  // namespace rt2
