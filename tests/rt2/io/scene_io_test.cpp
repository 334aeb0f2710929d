// tests/rt2/io/scene_io_test.cpp — scene loading (rt2/io/scene_io.h): TOML scenes, OBJ/MTL meshes,
// framing a bare OBJ, and the error contract: every problem is an rt2::Error whose message
// is one line starting with the file (and line, where there is one).
//
// Input files are written at run time into a fresh temporary folder; the example scenes are
// read from the source tree through RT2_SOURCE_DIR.
#include "rt2/io/scene_io.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

#include "rt2/bvh/accel.h"
#include "rt2/base/error.h"
#include "rt2/render/renderer.h"
#include "rt2/render/schedule.h"
#include "tests/rt2/error_of.h"
#include "tests/rt2/test_util.h"
#include "tests/rt2/temp_dir.h"

#ifndef RT2_SOURCE_DIR
#error "the build defines RT2_SOURCE_DIR as the repository root"
#endif

namespace rt2 {
namespace {

namespace fs = std::filesystem;
using test::error_of;

using test::TempDir;

std::string source_file(const std::string& name) {
  return std::string(RT2_SOURCE_DIR) + "/" + name;
}


bool contains(const std::string& s, std::string_view part) {
  return s.find(part) != std::string::npos;
}

// The contract: one line, starting with "file:line:" (just "file:" when line is 0), and
// saying `text`.
void expect_message(const std::string& msg, const std::string& file, int line,
                    std::string_view text) {
  EXPECT_FALSE(contains(msg, "\n")) << msg;
  EXPECT_FALSE(contains(msg, "\r")) << msg;
  const std::string prefix = file + ":" + (line > 0 ? std::to_string(line) + ":" : "");
  EXPECT_EQ(msg.rfind(prefix, 0), 0u) << "expected to start with '" << prefix << "': " << msg;
  EXPECT_TRUE(contains(msg, text)) << "expected '" << text << "' in: " << msg;
}

// Loads `toml` as a scene and expects an error at `line` saying `text`.
void expect_scene_error(std::string_view toml, int line, std::string_view text) {
  TempDir dir;
  const std::string path = dir.write("scene.toml", toml);
  expect_message(error_of([&] { load_scene(path); }), path, line, text);
}

struct BadScene {
  std::string toml;
  int line;
  std::string text;
};

void expect_scene_errors(const std::vector<BadScene>& cases) {
  for (const BadScene& c : cases) {
    SCOPED_TRACE(c.toml);
    expect_scene_error(c.toml, c.line, c.text);
  }
}

Scene load_text(const TempDir& dir, std::string_view toml) {
  return load_scene(dir.write("scene.toml", toml));
}

// Three lines, so that what follows starts at line 4.
const std::string kCamera = "[camera]\nposition = [0, 1, 5]\nlook_at = [0, 1, 0]\n";
// Lines 4-5: a material "red".
const std::string kRed = "[materials.red]\ndiffuse = [1, 0, 0]\n";

const std::string kTriangleObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

void expect_vec(const vec4& v, float x, float y, float z) {
  EXPECT_FLOAT_EQ(v[0], x);
  EXPECT_FLOAT_EQ(v[1], y);
  EXPECT_FLOAT_EQ(v[2], z);
  EXPECT_EQ(v[3], 0.0f);
}

void expect_near_vec(const vec4& v, float x, float y, float z) {
  EXPECT_NEAR(v[0], x, 1e-5f);
  EXPECT_NEAR(v[1], y, 1e-5f);
  EXPECT_NEAR(v[2], z, 1e-5f);
  EXPECT_EQ(v[3], 0.0f);
}

const Material& material_named(const Scene& s, const std::string& name) {
  const int i = s.find_material(name);
  EXPECT_GE(i, 0) << name;
  return s.materials.at(static_cast<std::size_t>(i < 0 ? 0 : i));
}

// ---- valid scenes -----------------------------------------------------------------------

TEST(SceneIo, FullSceneParsesWithTheRightValues) {
  TempDir dir;
  const Scene s = load_text(dir, R"(
[camera]
position = [0, 1.5, 6]
look_at = [0, 1.5, 0]
up = [0, 2, 0]
fov = 50

[world]
ambient = [0.3, 0.2, 0.1]
background = [0.05, 0.05, 0.1]

[materials.shiny]
ambient = [0.1, 0.2, 0.3]
diffuse = [0.4, 0.5, 0.6]
specular = [0.7, 0.8, 0.9]
shininess = 64
reflectivity = 0.25
transparency = 0.5
ior = 1.33
checker = { color = [0.2, 0.2, 0.2], scale = 0.5 }

[[lights]]
position = [5, 8, 5]
color = [1, 0.5, 0.25]
intensity = 2

[[lights]]
position = [-5, 8, 5]

[[spheres]]
center = [1, 2, 3]
radius = 4
material = "shiny"
)");
  EXPECT_EQ(s.camera.position(), vec4(0, 1.5f, 6));
  expect_near_vec(s.camera.forward(), 0, 0, -1);
  expect_near_vec(s.camera.up(), 0, 1, 0);
  EXPECT_FLOAT_EQ(s.camera.fov(), 50.0f);
  expect_vec(s.ambient, 0.3f, 0.2f, 0.1f);
  expect_vec(s.background, 0.05f, 0.05f, 0.1f);

  const Material& m = material_named(s, "shiny");
  expect_vec(m.ambient, 0.1f, 0.2f, 0.3f);
  expect_vec(m.diffuse, 0.4f, 0.5f, 0.6f);
  expect_vec(m.specular, 0.7f, 0.8f, 0.9f);
  EXPECT_FLOAT_EQ(m.shininess, 64.0f);
  EXPECT_FLOAT_EQ(m.reflectivity, 0.25f);
  EXPECT_FLOAT_EQ(m.transparency, 0.5f);
  EXPECT_FLOAT_EQ(m.ior, 1.33f);
  expect_vec(m.diffuse2, 0.2f, 0.2f, 0.2f);
  EXPECT_FLOAT_EQ(m.checker_scale, 0.5f);

  ASSERT_EQ(s.lights.size(), 2u);
  expect_vec(s.lights[0].position, 5, 8, 5);
  expect_vec(s.lights[0].color, 1, 0.5f, 0.25f);
  EXPECT_FLOAT_EQ(s.lights[0].intensity, 2.0f);
  expect_vec(s.lights[1].color, 1, 1, 1);  // defaults
  EXPECT_FLOAT_EQ(s.lights[1].intensity, 1.0f);

  ASSERT_EQ(s.spheres.size(), 1u);
  expect_vec(s.spheres[0].center, 1, 2, 3);
  EXPECT_FLOAT_EQ(s.spheres[0].radius, 4.0f);
  EXPECT_EQ(s.sphere_materials[0], static_cast<std::uint32_t>(s.find_material("shiny")));
  EXPECT_TRUE(s.planes.empty());
  EXPECT_TRUE(s.meshes.empty());
}

TEST(SceneIo, DefaultsApplyWhenOptionalKeysAreOmitted) {
  TempDir dir;
  const Scene s = load_text(dir,
                            "[camera]\nposition = [0, 0, 0]\ndirection = [0, 0, -3]\n"
                            "[materials.plain]\n");
  expect_near_vec(s.camera.forward(), 0, 0, -1);
  expect_near_vec(s.camera.up(), 0, 1, 0);
  EXPECT_FLOAT_EQ(s.camera.fov(), 60.0f);
  expect_vec(s.ambient, 0.2f, 0.2f, 0.2f);
  expect_vec(s.background, 0, 0, 0);
  const Material& m = material_named(s, "plain");
  const Material d;
  EXPECT_EQ(m.diffuse, d.diffuse);
  EXPECT_EQ(m.ambient, d.ambient);
  EXPECT_FLOAT_EQ(m.shininess, d.shininess);
  EXPECT_FLOAT_EQ(m.ior, d.ior);
  EXPECT_FLOAT_EQ(m.checker_scale, 0.0f);  // no checker
}

TEST(SceneIo, MaterialsMayBeDefinedAfterTheObjectsThatUseThem) {
  TempDir dir;
  const Scene s = load_text(dir, kCamera +
                                     "[[spheres]]\ncenter = [0, 0, 0]\nradius = 1\n"
                                     "material = \"late\"\n[materials.late]\n"
                                     "diffuse = [0, 0, 1]\n");
  ASSERT_EQ(s.spheres.size(), 1u);
  expect_vec(s.materials.at(s.sphere_materials[0]).diffuse, 0, 0, 1);
}

TEST(SceneIo, PlaneNormalIsNormalisedAndTheOffsetScaledWithIt) {
  TempDir dir;
  // 2y + 4 = 0 is the plane y = -2, whatever the length of the normal.
  const Scene s =
      load_text(dir, kCamera + kRed +
                         "[[planes]]\nnormal = [0, 2, 0]\noffset = 4\nmaterial = \"red\"\n"
                         "[[planes]]\nnormal = [0, 0, 5]\npoint = [1, 2, 3]\nmaterial = \"red\"\n");
  ASSERT_EQ(s.planes.size(), 2u);
  expect_vec(s.planes[0].n, 0, 1, 0);
  EXPECT_FLOAT_EQ(s.planes[0].d, 2.0f);
  expect_vec(s.planes[1].n, 0, 0, 1);
  EXPECT_FLOAT_EQ(s.planes[1].d, -3.0f);  // z = 3
}

TEST(SceneIo, RelativeMeshPathIsResolvedFromTheSceneFolder) {
  TempDir dir;
  dir.write("scenes/models/tri.obj", kTriangleObj);
  const std::string scene =
      dir.write("scenes/room.toml", kCamera + "[[meshes]]\nfile = \"models/tri.obj\"\n");
  // models/tri.obj is not under the working folder; and the scene's path may be relative.
  for (const fs::path& p : {fs::path(scene), fs::relative(scene, fs::current_path())}) {
    SCOPED_TRACE(p.string());
    const Scene s = load_scene(p.string());
    ASSERT_EQ(s.meshes.size(), 1u);
    EXPECT_EQ(s.meshes[0].triangle_count(), 1u);
    EXPECT_TRUE(fs::equivalent(s.meshes[0].name, dir.path("scenes/models/tri.obj")));
  }
}

TEST(SceneIo, MeshTransformScalesRotatesThenTranslates) {
  TempDir dir;
  dir.write("tri.obj", kTriangleObj);
  const Scene s = load_text(dir, kCamera +
                                     "[[meshes]]\nfile = \"tri.obj\"\nscale = 2\n"
                                     "rotate = [0, 0, 90]\ntranslate = [10, 0, 0]\n"
                                     "[[meshes]]\nfile = \"tri.obj\"\nscale = [1, 3, 1]\n");
  ASSERT_EQ(s.meshes.size(), 2u);
  const Mesh& m = s.meshes[0];
  // (1,0,0) -> scale (2,0,0) -> rotate 90 about z (0,2,0) -> translate (10,2,0).
  const auto& f = m.faces.at(0);
  expect_near_vec(m.positions[f[0]], 10, 0, 0);
  expect_near_vec(m.positions[f[1]], 10, 2, 0);
  expect_near_vec(m.positions[f[2]], 8, 0, 0);
  const Mesh& n = s.meshes[1];
  expect_near_vec(n.positions[n.faces[0][2]], 0, 3, 0);
}

TEST(SceneIo, InstancesShareOneMeshAndPlaceItByTransformOrMatrix) {
  TempDir dir;
  dir.write("tri.obj", kTriangleObj);
  const Scene s = load_text(
      dir, kCamera + kRed +
               "[[instances]]\nmesh = \"tri.obj\"\nscale = 2\nrotate = [0, 0, 90]\n"
               "translate = [10, 0, 0]\n"
               "[[instances]]\nmesh = \"tri.obj\"\nmaterial = \"red\"\n"
               "matrix = [[1, 0, 0, 5], [0, 3, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]\n");
  ASSERT_EQ(s.instanced_meshes.size(), 1u);  // the file read once
  ASSERT_EQ(s.instances.size(), 2u);
  EXPECT_TRUE(s.meshes.empty());
  EXPECT_EQ(s.triangle_count(), 1u);
  EXPECT_EQ(s.placed_triangle_count(), 2u);
  // (1,0,0) -> scale (2,0,0) -> rotate 90 about z (0,2,0) -> translate (10,2,0)
  const auto p = s.instances[0].to_world.point({1, 0, 0});
  EXPECT_NEAR(p[0], 10.0, 1e-12);
  EXPECT_NEAR(p[1], 2.0, 1e-12);
  EXPECT_EQ(s.instances[0].material, kMeshMaterials);
  EXPECT_EQ(s.instances[1].material, std::uint32_t(s.find_material("red")));
  EXPECT_EQ(s.instances[1].to_world.m[1][1], 3.0);
  EXPECT_EQ(s.instances[1].to_world.m[0][3], 5.0);
  const Aabb b = s.bounds();
  EXPECT_NEAR(b.lo[0], 5.0f, 1e-4f);
  EXPECT_NEAR(b.hi[0], 10.0f, 1e-4f);
}

TEST(SceneIo, BadInstancesAreRefusedWithTheirKeyAndLine) {
  TempDir dir;
  dir.write("tri.obj", kTriangleObj);
  const auto bad = [&](const std::string& body, int line, std::string_view text) {
    SCOPED_TRACE(body);
    const std::string path = dir.write("scene.toml", kCamera + "[[instances]]\n" + body);
    expect_message(error_of([&] { load_scene(path); }), path, line, text);
  };
  const std::string tri = "mesh = \"" + dir.path("tri.obj") + "\"\n";
  bad(tri + "scale = [1, 0, 1]\n", 6, "must not be zero");
  bad(tri + "matrix = [[1, 0, 0, 0], [0, 1, 0, 0], [1, 0, 0, 0]]\n", 4, "singular");
  bad(tri + "matrix = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 1, 1]]\n", 6,
      "must be 0 0 0 1");
  bad(tri + "matrix = [[1, 0, 0, 0], [0, 1, 0, 0]]\n", 6, "3 or 4 rows");
  bad(tri + "matrix = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]\ntranslate = [1, 2, 3]\n", 7,
      "give matrix or translate");
  bad(tri + "matrix = [[1e300, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]\n", 6, "matrix[0][0]");
  bad(tri + "material = \"nothing\"\n", 6, "undefined material 'nothing'");
  bad(tri + "scale = 1e15\n", 4, "too large or too small for float arithmetic");
  bad(tri + "scale = [1e-14, 1, 1]\n", 4, "too large or too small for float arithmetic");
  bad("mesh = \"none.obj\"\n", 5, "none.obj");
  bad(tri + "rotation = [0, 0, 0]\n", 6, "unknown key 'rotation'");
}

TEST(SceneIo, MeshMaterialOverridesTheMtlMaterials) {
  TempDir dir;
  const Scene s = load_text(dir, kCamera + kRed + "[[meshes]]\nfile = \"" +
                                     source_file("scenes/tetra.obj") + "\"\nmaterial = \"red\"\n");
  ASSERT_EQ(s.meshes.size(), 1u);
  const auto red = static_cast<std::uint32_t>(s.find_material("red"));
  for (const auto m : s.meshes[0].face_materials) EXPECT_EQ(m, red);
  EXPECT_EQ(s.find_material("tetra.obj:mirror"), -1);  // the MTL is not used at all
}

TEST(SceneIo, MtlMirrorGetsReflectivityFromKsWithIllum3) {
  Scene s;
  const Mesh m = load_obj(source_file("scenes/tetra.obj"), s);
  EXPECT_EQ(m.triangle_count(), 4u);
  EXPECT_EQ(m.positions.size(), 4u);
  const Material& mirror = material_named(s, "tetra.obj:mirror");
  EXPECT_FLOAT_EQ(mirror.reflectivity, 0.9f);
  EXPECT_FLOAT_EQ(mirror.transparency, 0.0f);
  expect_vec(mirror.specular, 0.9f, 0.9f, 0.9f);
  expect_vec(mirror.diffuse, 0.05f, 0.05f, 0.05f);
  EXPECT_FLOAT_EQ(mirror.shininess, 200.0f);
  for (const auto f : m.face_materials)
    EXPECT_EQ(f, static_cast<std::uint32_t>(s.find_material("tetra.obj:mirror")));
}

TEST(SceneIo, MtlGlassGetsTransparencyReflectivityAndIor) {
  TempDir dir;
  dir.write("g.mtl",
            "newmtl clear\nKs 0.5 0.6 0.4\nNi 1.33\nillum 7\n"  // d absent: 0.9
            "newmtl tinted\nKs 0.2 0.2 0.2\nd 0.3\nillum 4\n"   // 1 - d
            "newmtl faded\nd 0.25\nillum 2\n"                   // plain transparency
            "newmtl old\nTr 0.4\n");                            // Tr without d
  const std::string obj = dir.write("g.obj",
                                    "mtllib g.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                    "usemtl clear\nf 1 2 3\nusemtl tinted\nf 1 2 3\n"
                                    "usemtl faded\nf 1 2 3\nusemtl old\nf 1 2 3\n");
  Scene s;
  load_obj(obj, s);
  const Material& clear = material_named(s, "g.obj:clear");
  EXPECT_FLOAT_EQ(clear.transparency, 0.9f);
  EXPECT_FLOAT_EQ(clear.reflectivity, 0.6f);
  EXPECT_FLOAT_EQ(clear.ior, 1.33f);
  const Material& tinted = material_named(s, "g.obj:tinted");
  EXPECT_NEAR(tinted.transparency, 0.7f, 1e-6f);
  EXPECT_FLOAT_EQ(tinted.reflectivity, 0.2f);
  EXPECT_FLOAT_EQ(tinted.ior, 1.5f);  // no Ni: the default, not tinyobjloader's 1
  const Material& faded = material_named(s, "g.obj:faded");
  EXPECT_FLOAT_EQ(faded.transparency, 0.75f);
  EXPECT_FLOAT_EQ(faded.reflectivity, 0.0f);
  EXPECT_NEAR(material_named(s, "g.obj:old").transparency, 0.4f, 1e-6f);
}

TEST(SceneIo, MtlKrSetsReflectivityAndOutOfRangeValuesAreClamped) {
  TempDir dir;
  dir.write("k.mtl", "newmtl a\nKr 0.7\nnewmtl b\nKd 2 -1 0.5\nNs -5\nNi -2\nKr 3\n");
  const std::string obj = dir.write("k.obj",
                                    "mtllib k.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                    "usemtl a\nf 1 2 3\nusemtl b\nf 1 2 3\n");
  Scene s;
  load_obj(obj, s);
  EXPECT_FLOAT_EQ(material_named(s, "k.obj:a").reflectivity, 0.7f);
  const Material& b = material_named(s, "k.obj:b");
  EXPECT_FLOAT_EQ(b.reflectivity, 1.0f);
  expect_vec(b.diffuse, 1.0f, 0.0f, 0.5f);
  EXPECT_FLOAT_EQ(b.shininess, 0.0f);
  EXPECT_FLOAT_EQ(b.ior, 1.5f);
  EXPECT_NO_THROW(s.validate());
}

// An OBJ triangle using material `name` of the MTL `mtl`; the scene it loads into.
Scene load_with_mtl(const TempDir& dir, const std::string& mtl, const std::string& name = "m") {
  dir.write("t.mtl", mtl);
  Scene s;
  load_obj(dir.write("t.obj", "mtllib t.mtl\nusemtl " + name + "\n" + kTriangleObj), s);
  return s;
}

TEST(SceneIo, MtlColourOfOneNumberIsGrey) {
  TempDir dir;
  const Scene s = load_with_mtl(dir, "newmtl m\nKa 0.1\nKd 0.5\nKs 0.25\nNs 10\n");
  const Material& m = material_named(s, "t.obj:m");
  expect_vec(m.diffuse, 0.5f, 0.5f, 0.5f);  // not (0.5, 0, 0), dark red
  expect_vec(m.ambient, 0.1f, 0.1f, 0.1f);
  expect_vec(m.specular, 0.25f, 0.25f, 0.25f);
}

TEST(SceneIo, BadMtlNumbersAreErrorsNamingTheMtlLine) {
  for (const auto& [mtl, line, text] : std::vector<std::tuple<std::string, int, std::string>>{
           {"newmtl m\nNs nan\n", 2, "Ns must be a finite number (got 'nan')"},
           {"newmtl m\nKd 1 1 1\nKd nan\n", 3, "Kd must be a finite number (got 'nan')"},
           {"newmtl m\nKd red green blue\n", 2, "Kd must be a number (got 'red')"},
       }) {
    TempDir dir;
    const std::string path = dir.write("t.mtl", mtl);
    const std::string obj = dir.write("t.obj", "mtllib t.mtl\nusemtl m\n" + kTriangleObj);
    Scene s;
    expect_message(error_of([&] { load_obj(obj, s); }), path, line, text);
  }
}

TEST(SceneIo, MtlShininessZeroHasNoHighlight) {
  TempDir dir;
  const Scene s = load_with_mtl(dir, "newmtl m\nKd 0.5\nKs 0.5\nNs 0\n");
  expect_vec(material_named(s, "t.obj:m").specular, 0, 0, 0);
}

TEST(SceneIo, UsemtlNamesTheRestOfTheLine) {
  TempDir dir;
  testing::internal::CaptureStderr();
  const Scene s = load_with_mtl(dir, "newmtl Hard Wood\nKd 0.6 0.4 0.2\n", "Hard Wood  ");
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  expect_vec(material_named(s, "t.obj:Hard Wood").diffuse, 0.6f, 0.4f, 0.2f);
}

TEST(SceneIo, MtlUnsupportedTexturesAreOneWarningPerFileAndMissingFilesAWarningEach) {
  TempDir dir;
  testing::internal::CaptureStderr();
  const Scene s =
      load_with_mtl(dir, "newmtl m\nKd 0.5\nmap_Kd wood.png\nmap_bump b.png\nbump c.png\n");
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(err, "warning: " + dir.path("t.mtl") +
                     ":4: 'map_bump' is not supported; it and the other unsupported texture "
                     "statements of this file are ignored (rt2 reads map_Kd, map_Ke, map_Pr, "
                     "map_Pm and norm)\nwarning: " +
                     dir.path("t.mtl") + ":3: texture 'wood.png' not found; ignored\n");
  const Material& m = material_named(s, "t.obj:m");
  expect_vec(m.diffuse, 0.5f, 0.5f, 0.5f);
  EXPECT_EQ(m.base_color_texture, kNoTexture);
  EXPECT_TRUE(s.textures.empty());
}

TEST(SceneIo, MtlTextureFilesAreAddedOncePerFileAndColourSpace) {
  TempDir dir;
  dir.write("wood.png", "not decoded before the scene is compiled");
  const Scene s = load_with_mtl(dir,
                                "newmtl m\nKd 0.5\nPr 0.3\nmap_Kd wood.png\nmap_Ke wood.png\n"
                                "map_Pr wood.png\n");
  ASSERT_EQ(s.textures.size(), 2u);
  const Material& m = material_named(s, "t.obj:m");
  EXPECT_EQ(m.model, Shading::pbr);
  EXPECT_EQ(m.base_color_texture, 0u);
  EXPECT_EQ(m.emissive_texture, 0u);
  EXPECT_EQ(m.roughness_texture, 1u);
  EXPECT_EQ(s.textures[0].path, dir.path("wood.png"));
  EXPECT_TRUE(s.textures[0].srgb);
  EXPECT_FALSE(s.textures[1].srgb);  // roughness is data, not a colour
}

TEST(SceneIo, MissingMtlLibraryIsOneWarningLineNotAnError) {
  TempDir dir;
  const std::string obj = dir.write("m.obj",
                                    "mtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                    "usemtl shiny\nf 1 2 3\n");
  Scene s;
  testing::internal::CaptureStderr();
  const Mesh m = load_obj(obj, s);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(err, "warning: " + obj +
                     ": material library 'gone.mtl' not found; using the default material\n");
  ASSERT_EQ(m.triangle_count(), 1u);
  EXPECT_EQ(m.face_materials[0], static_cast<std::uint32_t>(s.find_material("default")));
}

TEST(SceneIo, ObjWithoutMaterialsGetsOneSharedDefaultMaterial) {
  TempDir dir;
  dir.write("tri.obj", kTriangleObj);
  const Scene s =
      load_text(dir, kCamera + "[[meshes]]\nfile = \"tri.obj\"\n[[meshes]]\nfile = \"tri.obj\"\n");
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.material_names.at(0), "default");
  EXPECT_EQ(s.meshes[0].face_materials[0], 0u);
  EXPECT_EQ(s.meshes[1].face_materials[0], 0u);
  expect_vec(s.materials[0].diffuse, 0.7f, 0.7f, 0.7f);  // rt2::Material's grey
}

TEST(SceneIo, DegenerateTrianglesAreDroppedAndCounted) {
  TempDir dir;
  const std::string obj = dir.write("d.obj",
                                    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\n"
                                    "f 1 2 3\nf 1 2 4\nf 1 1 3\n");  // collinear, repeated
  Scene s;
  const Mesh m = load_obj(obj, s);
  EXPECT_EQ(m.triangle_count(), 1u);
  EXPECT_EQ(m.face_materials.size(), 1u);
  EXPECT_EQ(s.degenerate_triangles, 2u);
}

TEST(SceneIo, PolygonsAreTriangulated) {
  TempDir dir;
  const std::string obj = dir.write("q.obj",
                                    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv -1 0.5 0\n"
                                    "f 1 2 3 4\nf 1 2 3 4 5\n");
  Scene s;
  const Mesh m = load_obj(obj, s);
  EXPECT_EQ(m.triangle_count(), 2u + 3u);
  EXPECT_EQ(s.degenerate_triangles, 0u);
}

// The area of a mesh's triangles, in double.
double mesh_area(const Mesh& m) {
  double sum = 0.0;
  for (const auto& f : m.faces) {
    const vec4 &a = m.positions[f[0]], &b = m.positions[f[1]], &c = m.positions[f[2]];
    const double ux = double(b[0]) - a[0], uy = double(b[1]) - a[1], uz = double(b[2]) - a[2];
    const double vx = double(c[0]) - a[0], vy = double(c[1]) - a[1], vz = double(c[2]) - a[2];
    const double x = uy * vz - uz * vy, y = uz * vx - ux * vz, z = ux * vy - uy * vx;
    sum += 0.5 * std::sqrt(x * x + y * y + z * z);
  }
  return sum;
}

// The OBJ text of one polygon in the plane z = 0: its corners as vertices, one face.
std::string polygon_obj(const std::vector<std::pair<double, double>>& corners) {
  std::string obj;
  for (const auto& [x, y] : corners)
    obj += "v " + std::to_string(x) + " " + std::to_string(y) + " 0\n";
  obj += "f";
  for (std::size_t i = 1; i <= corners.size(); ++i) obj += " " + std::to_string(i);
  return obj + "\n";
}

// A ring as LightWave writes it: the outer circle, a bridge edge to the inner one, the inner
// one the other way round, and back along the bridge (the bridge's ends repeated).
std::vector<std::pair<double, double>> bridged_ring(int n, double outer, double inner) {
  std::vector<std::pair<double, double>> p;
  const auto at = [](double r, int k, int count) {
    const double a = 2 * 3.14159265358979 * k / count;
    return std::pair(r * std::cos(a), r * std::sin(a));
  };
  for (int k = 0; k <= n; ++k) p.push_back(at(outer, k % n, n));
  for (int k = n; k >= 0; --k) p.push_back(at(inner, k % n, n));
  return p;
}

// Twice the signed area of the polygon (shoelace), and whether a point is inside it (even-odd:
// a bridge walked twice does not count).
double twice_area(const std::vector<std::pair<double, double>>& p) {
  double s = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto [x0, y0] = p[i];
    const auto [x1, y1] = p[(i + 1) % p.size()];
    s += x0 * y1 - x1 * y0;
  }
  return s;
}

bool inside(const std::vector<std::pair<double, double>>& p, double x, double y) {
  bool in = false;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
    const auto [xi, yi] = p[i];
    const auto [xj, yj] = p[j];
    if ((yi > y) != (yj > y) && x < (xj - xi) * (y - yi) / (yj - yi) + xi) in = !in;
  }
  return in;
}

// The mesh of the polygon covers exactly the polygon: its area, and no triangle outside (a
// filled hole, a fan across a notch).
void expect_covers_exactly(const Mesh& m, const std::vector<std::pair<double, double>>& p) {
  EXPECT_NEAR(mesh_area(m), 0.5 * std::fabs(twice_area(p)), 1e-5 * std::fabs(twice_area(p)));
  std::size_t outside = 0;
  for (const auto& f : m.faces) {
    double x = 0, y = 0;
    for (const std::uint32_t i : f) {
      x += m.positions[i][0] / 3.0;
      y += m.positions[i][1] / 3.0;
    }
    outside += !inside(p, x, y);
  }
  EXPECT_EQ(outside, 0u);
}

TEST(SceneIo, PolygonsWithAHoleJoinedByABridgeKeepTheHole) {
  TempDir dir;
  // The square frame (a broken fan before) and a LightWave ring (a filled disc before).
  const std::vector<std::pair<double, double>> frame{{0, 0}, {4, 0}, {4, 4}, {0, 4}, {0, 0},
                                                     {1, 1}, {1, 3}, {3, 3}, {3, 1}, {1, 1}};
  for (const auto& p : {frame, bridged_ring(32, 1.0, 0.93), bridged_ring(500, 1.0, 0.999)}) {
    Scene s;
    const Mesh m = load_obj(dir.write("p.obj", polygon_obj(p)), s);
    EXPECT_EQ(m.triangle_count(), p.size() - 2);
    EXPECT_EQ(s.degenerate_triangles, 0u);
    expect_covers_exactly(m, p);
  }
}

// Debian's assimp-testmodels has the LightWave original: a ring of 66 corners in the plane
// x = -1.146. Tested when the package is installed.
TEST(SceneIo, TheLightWaveRingOfAssimpsTestModelsKeepsItsHole) {
  const std::string path = "/usr/share/assimp/models/OBJ/concave_polygon.obj";
  if (!fs::exists(path)) {
    std::printf("[ skipped  ] %s is not installed (apt-get install assimp-testmodels)\n",
                path.c_str());
    return;
  }
  testing::internal::CaptureStderr();
  Scene s;
  Mesh m = load_obj(path, s);
  testing::internal::GetCapturedStderr();
  EXPECT_EQ(m.triangle_count(), 64u);
  // In its own plane (y, z): the face's corners from the file, in order.
  std::ifstream in(path);
  std::vector<std::pair<double, double>> v, p;
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::string key;
    words >> key;
    double x, y, z;
    if (key == "v" && words >> x >> y >> z) v.emplace_back(y, z);
    if (key != "f") continue;
    for (std::string corner; words >> corner;) p.push_back(v.at(std::stoul(corner) - 1));
  }
  ASSERT_EQ(p.size(), 66u);
  for (vec4& q : m.positions) q = vec4(q[1], q[2], 0.0f);
  expect_covers_exactly(m, p);
}

TEST(SceneIo, ConcaveQuadsAreSplitThroughTheirReflexCorner) {
  TempDir dir;
  // A dart: the diagonal through the reflex corner (1, 0.2) is the longer one.
  const std::vector<std::pair<double, double>> dart{{0, 0}, {1, 0.2}, {2, 0}, {1, 3}};
  Scene s;
  const Mesh m = load_obj(dir.write("d.obj", polygon_obj(dart)), s);
  ASSERT_EQ(m.triangle_count(), 2u);
  expect_covers_exactly(m, dart);
}

TEST(SceneIo, ConvexQuadsAreSplitAlongTheirShorterDiagonalAsBefore) {
  TempDir dir;
  Scene s;
  const Mesh m =
      load_obj(dir.write("q.obj", "v 0 0 0\nv 2 -1 0\nv 4 0 0\nv 2 1 0\nf 1 2 3 4\n"), s);
  ASSERT_EQ(m.triangle_count(), 2u);
  // Corners 2 and 4 (the short diagonal) in both triangles: (1, 2, 4) and (2, 3, 4).
  const auto x = [&](std::size_t f, int k) { return m.positions[m.faces[f][k]][0]; };
  EXPECT_EQ(x(0, 0), 0.0f);
  EXPECT_EQ(x(0, 1), 2.0f);
  EXPECT_EQ(x(0, 2), 2.0f);
  EXPECT_EQ(x(1, 0), 2.0f);
  EXPECT_EQ(x(1, 1), 4.0f);
  EXPECT_EQ(x(1, 2), 2.0f);
}

// A single polygon of 100,000 corners: far too many for an ear clipper without a search
// structure (tinyobjloader's) to finish in seconds.
// The work bound is tests/rt2/io/polygon_triangulation_test.cpp's (counted, not timed).
TEST(SceneIo, AHundredThousandCornerPolygonLoadsAsItsTriangles) {
  TempDir dir;
  const int n = 100000;
  std::string obj;
  obj.reserve(40 * n);
  for (int k = 0; k < n; ++k) {
    const double a = 2 * 3.14159265358979 * k / n;
    obj += "v " + std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
  }
  obj += "f";
  for (int k = 1; k <= n; ++k) obj += " " + std::to_string(k);
  const std::string path = dir.write("circle.obj", obj + "\n");
  Scene s;
  const auto start = std::chrono::steady_clock::now();
  const Mesh m = load_obj(path, s);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("[ measure  ] a polygon of %d corners loads in %.3f s\n", n, seconds);
  EXPECT_EQ(m.triangle_count() + s.degenerate_triangles, std::size_t(n - 2));
  EXPECT_NEAR(mesh_area(m), 3.14159265358979, 1e-3);
}

TEST(SceneIo, NormalsAreKeptPerCornerAsUnitVectors) {
  TempDir dir;
  // Vertex 1 has two different normals: it becomes two positions.
  const std::string obj = dir.write("n.obj",
                                    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                    "vn 0 0 2\nvn 3 0 0\n"
                                    "f 1//1 2//1 3//1\nf 1//2 3//2 4//2\n");
  Scene s;
  const Mesh m = load_obj(obj, s);
  ASSERT_EQ(m.normals.size(), m.positions.size());
  EXPECT_EQ(m.positions.size(), 6u);
  expect_vec(m.normals[m.faces[0][0]], 0, 0, 1);
  expect_vec(m.normals[m.faces[1][0]], 1, 0, 0);
  EXPECT_EQ(m.positions[m.faces[0][0]], m.positions[m.faces[1][0]]);
}

TEST(SceneIo, FrameObjLooksAtTheMeshCentreWithOneLightAndOneGroundPlane) {
  const Scene s = frame_obj(source_file("scenes/tetra.obj"));
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.lights.size(), 1u);
  ASSERT_EQ(s.planes.size(), 1u);
  const Aabb box = s.meshes[0].bounds();
  const vec4 centre = box.center();
  // The ray through the image centre goes through the mesh centre.
  const Ray r = s.camera.ray(50.0f, 50.0f, 100, 100);
  const vec4 to_centre = normalize(centre - r.org);
  EXPECT_GT(float(dot(to_centre, r.dir)), 0.99999f);
  // Every corner of the box is in view (square image).
  const float tan_half = std::tan(0.5f * s.camera.fov() * 3.14159265f / 180.0f);
  for (int i = 0; i < 8; ++i) {
    const vec4 corner((i & 1 ? box.hi : box.lo)[0], (i & 2 ? box.hi : box.lo)[1],
                      (i & 4 ? box.hi : box.lo)[2]);
    const vec4 d = corner - s.camera.position();
    const float z = dot(d, s.camera.forward());
    ASSERT_GT(z, 0.0f);
    EXPECT_LE(std::fabs(float(dot(d, s.camera.right())) / z), tan_half) << i;
    EXPECT_LE(std::fabs(float(dot(d, s.camera.up())) / z), tan_half) << i;
  }
  // The light is above the mesh; the ground is the plane y = lo.y - R / 1000 with a checker.
  EXPECT_GT(s.lights[0].position[1], box.hi[1]);
  expect_vec(s.planes[0].n, 0, 1, 0);
  const vec4 half = box.extent() * 0.5f;
  const float radius = std::sqrt(float(dot(half, half)));
  EXPECT_FLOAT_EQ(s.planes[0].d, -(box.lo[1] - 1e-3f * radius));
  EXPECT_GT(s.materials.at(s.plane_materials[0]).checker_scale, 0.0f);
  EXPECT_NE(s.find_material("tetra.obj:mirror"), -1);
  EXPECT_EQ(s.find_material("default"), -1);  // only materials that faces use are added
}

// Renders `s` (96 x 72, no recursion) with and without its ground plane: wherever the mesh is
// seen without the plane, the plane must not change the pixel (at the mesh's lowest y it
// z-fought with a floor in the mesh, and hid a flat mesh).
void expect_ground_never_shows_through(const Scene& s) {
  RenderSettings st;
  st.width = 96;
  st.height = 72;
  st.depth = 0;
  Scene bare = s;
  bare.planes.clear();
  bare.plane_materials.clear();
  const Image with = test::render_scene(s, st), without = test::render_scene(bare, st);
  std::size_t mesh_pixels = 0, changed = 0;
  for (std::size_t i = 0; i < without.rgb.size(); i += 3) {
    const bool background = without.rgb[i] == s.background[0] &&
                            without.rgb[i + 1] == s.background[1] &&
                            without.rgb[i + 2] == s.background[2];
    if (background) continue;
    ++mesh_pixels;
    changed += with.rgb[i] != without.rgb[i] || with.rgb[i + 1] != without.rgb[i + 1] ||
               with.rgb[i + 2] != without.rgb[i + 2];
  }
  EXPECT_GT(mesh_pixels, 200u);
  EXPECT_EQ(changed, 0u) << "of " << mesh_pixels << " mesh pixels";
}

TEST(SceneIo, TheGroundOfAFramedObjNeverShowsThroughTheMesh) {
  // The Cornell room's floor lies at its lowest y; so does all of a flat quad.
  expect_ground_never_shows_through(frame_obj(source_file("scenes/cornell_room.obj")));
  TempDir dir;
  expect_ground_never_shows_through(
      frame_obj(dir.write("flat.obj", "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nf 1 4 3 2\n")));
}

TEST(SceneIo, LoadSceneFramesABareObjAndDispatchesOnTheExtension) {
  TempDir dir;
  const std::string obj = dir.write("Tri.OBJ", kTriangleObj);
  const Scene s = load_scene(obj);
  EXPECT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.planes.size(), 1u);
  const std::string other = dir.write("scene.json", "{}");
  expect_message(error_of([&] { load_scene(other); }), other, 0, "unknown file extension '.json'");
}

TEST(SceneIo, LightRangeAndLightFieldAreRead) {
  TempDir dir;
  const Scene s = load_text(dir, R"(
[camera]
position = [0, 1, 5]
look_at = [0, 0, 0]
[[lights]]
position = [0, 5, 0]
range = 2.5
[[lights]]
position = [0, 6, 0]
[light_field]
count = 1000
min = [-2, 0, -1]
max = [2, 3, 1]
range = [0.5, 1.5]
color = [1, 0.5, 0.25]
intensity = 0.75
seed = 7
)");
  ASSERT_EQ(s.lights.size(), 1002u);
  EXPECT_FLOAT_EQ(s.lights[0].range, 2.5f);
  EXPECT_FALSE(s.lights[1].has_range());
  ASSERT_TRUE(s.light_field.has_value());
  EXPECT_EQ(s.light_field->first, 2u);
  for (std::size_t i = 2; i < s.lights.size(); ++i) {
    const Light& l = s.lights[i];
    ASSERT_GE(l.range, 0.5f);
    ASSERT_LE(l.range, 1.5f);
    for (int a = 0; a < 3; ++a) {
      ASSERT_GE(l.position[a], s.light_field->box.lo[a]);
      ASSERT_LE(l.position[a], s.light_field->box.hi[a]);
    }
    ASSERT_FLOAT_EQ(l.intensity, 0.75f);
    ASSERT_FLOAT_EQ(l.color[1], 0.5f);
  }
  // More lights (rt2cpr --lights) continue the field and keep its first lights in place; a
  // given range applies to the field's lights, not to the [[lights]].
  Scene more = s;
  set_light_count(more, 1500);
  ASSERT_EQ(more.lights.size(), 1500u);
  for (std::size_t i = 0; i < s.lights.size(); ++i)
    ASSERT_EQ(float(dot(more.lights[i].position - s.lights[i].position,
                        more.lights[i].position - s.lights[i].position)), 0.0f);
  EXPECT_FLOAT_EQ(more.lights[1001].range, s.lights[1001].range);
  set_light_count(more, 1600, RangeInterval{0.25f, 0.25f});
  EXPECT_FLOAT_EQ(more.lights[1550].range, 0.25f);
  EXPECT_FLOAT_EQ(more.lights[1001].range, 0.25f);
  EXPECT_FLOAT_EQ(more.lights[0].range, 2.5f);
  EXPECT_EQ(float(dot(more.lights[1001].position - s.lights[1001].position,
                      more.lights[1001].position - s.lights[1001].position)), 0.0f);
  // Fewer lights keep the first ones.
  set_light_count(more, 3);
  EXPECT_EQ(more.lights.size(), 3u);
}

TEST(SceneIo, ExampleScenesLoad) {
  const Scene glass = load_scene(source_file("scenes/glass.toml"));
  EXPECT_EQ(glass.lights.size(), 2u);
  EXPECT_EQ(glass.planes.size(), 1u);
  EXPECT_GE(glass.spheres.size(), 4u);
  EXPECT_FLOAT_EQ(material_named(glass, "glass").transparency, 0.9f);
  EXPECT_FLOAT_EQ(material_named(glass, "glass").ior, 1.5f);
  EXPECT_GT(material_named(glass, "mirror").reflectivity, 0.5f);

  const Scene cornell = load_scene(source_file("scenes/cornell.toml"));
  ASSERT_EQ(cornell.meshes.size(), 1u);
  EXPECT_EQ(cornell.meshes[0].triangle_count(), 10u);
  EXPECT_EQ(cornell.spheres.size(), 2u);
  EXPECT_EQ(cornell.degenerate_triangles, 0u);
  EXPECT_NE(cornell.find_material("cornell_room.obj:red"), -1);
}

TEST(SceneIo, TheExampleInFormatMdLoads) {
  std::ifstream in(source_file("scenes/FORMAT.md"));
  const std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t begin = doc.find("```toml\n");
  ASSERT_NE(begin, std::string::npos);
  const std::size_t end = doc.find("```", begin + 8);
  ASSERT_NE(end, std::string::npos);
  TempDir dir;
  fs::copy_file(source_file("scenes/tetra.obj"), dir.path("tetra.obj"));
  fs::copy_file(source_file("scenes/tetra.mtl"), dir.path("tetra.mtl"));
  const Scene s = load_text(dir, doc.substr(begin + 8, end - begin - 8));
  EXPECT_FLOAT_EQ(s.camera.fov(), 50.0f);
  EXPECT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.spheres.size(), 1u);
  ASSERT_EQ(s.planes.size(), 2u);
  EXPECT_FLOAT_EQ(s.planes[1].d, 5.0f);  // through (0, 0, -5)
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].triangle_count(), 4u);
  EXPECT_FLOAT_EQ(material_named(s, "glass").transparency, 0.9f);
  EXPECT_FLOAT_EQ(material_named(s, "floor").checker_scale, 1.0f);
}

// ---- file-level errors ------------------------------------------------------------------

TEST(SceneIo, MissingFileIsAnErrorNamingIt) {
  TempDir dir;
  const std::string path = dir.path("nope.toml");
  expect_message(error_of([&] { load_scene(path); }), path, 0, "not found");
  const std::string obj = dir.path("nope.obj");
  expect_message(error_of([&] { load_scene(obj); }), obj, 0, "not found");
}

TEST(SceneIo, DirectoryOrDeviceIsAnError) {
  TempDir dir;
  fs::create_directories(dir.path("d.toml"));
  const std::string path = dir.path("d.toml");
  expect_message(error_of([&] { load_scene(path); }), path, 0, "directory");
  expect_message(error_of([&] { load_toml_scene("/dev/zero"); }), "/dev/zero", 0,
                 "not a regular file");
}

TEST(SceneIo, EmptyFileIsAnError) { expect_scene_error("", 0, "empty"); }

TEST(SceneIo, InvalidUtf8IsAnErrorWithItsLine) {
  expect_scene_errors({
      {kCamera + "# caf\xC3\x28\n", 4, "utf-8"},
      {kCamera + "x = \"\xFF\xFE\"\n", 4, "utf-8"},
  });
}

TEST(SceneIo, Utf16IsAnErrorOnOneLine) {
  // "[camera]" in UTF-16 LE with and without a byte-order mark.
  const std::string bare("[\0c\0a\0m\0e\0r\0a\0]\0\n\0", 18);
  expect_scene_errors({
      {"\xFF\xFE" + bare, 0, "UTF-16"},
      {"\xFE\xFF" + std::string("\0[\0]", 4), 0, "UTF-16"},
      {bare, 1, "NUL byte"},
  });
}

TEST(SceneIo, BinaryGarbageIsAnErrorOnOneLine) {
  std::string junk;
  std::mt19937 random(42);
  for (int i = 0; i < 4096; ++i) junk += static_cast<char>(random() % 255 + 1);  // no NUL
  TempDir dir;
  const std::string path = dir.write("junk.toml", junk);
  expect_message(error_of([&] { load_scene(path); }), path, 0, "");
  expect_scene_error(
      "\x7F"
      "ELF\x02\x01\x01\n",
      1, "");
}

TEST(SceneIo, SyntaxErrorNamesLineAndColumn) {
  TempDir dir;
  const std::string path = dir.write("s.toml", kCamera + "fov = \n");
  const std::string msg = error_of([&] { load_scene(path); });
  expect_message(msg, path, 4, "invalid TOML");
  EXPECT_TRUE(contains(msg, path + ":4:7:")) << msg;
  expect_scene_errors({
      {kCamera + "fov = 50\nfov = 60\n", 5, "invalid TOML"},  // redefined
      {kCamera + "[camera]\n", 4, "invalid TOML"},            // table twice
      {kCamera + "note = \"unterminated\n", 4, "invalid TOML"},
      {kCamera + "x = \"\"\"never closed\n\n", 5, "end-of-file"},  // toml++ points at the end
  });
}

TEST(SceneIo, DeepNestingIsAnErrorNotACrash) {
  const int n = 100000;
  std::string arrays = "a = " + std::string(n, '[') + std::string(n, ']') + "\n";
  std::string inline_tables = "a = ";
  for (int i = 0; i < n / 10; ++i) inline_tables += "{b=";
  inline_tables += "1" + std::string(n / 10, '}') + "\n";
  std::string dotted = "a", header = "[a", digits = "1";
  for (int i = 0; i < n; ++i) {
    dotted += ".a";
    header += ".a";
    digits += ".1";
  }
  expect_scene_errors({
      {arrays, 1, "nested"},
      {inline_tables, 1, "nested"},
      {dotted + " = 1\n", 1, "nested"},
      {header + "]\n", 1, "nested"},
      {digits + " = 1\n", 1, "nested"},
      {dotted + " = \n", 1, "nested"},  // a syntax error after deep keys
      {"x = [\n" + std::string(300, '{') + "\n", 2, ""},
  });
}

// ---- keys, types and values -------------------------------------------------------------

TEST(SceneIo, UnknownKeyIsNamedWithItsLineAndASuggestion) {
  TempDir dir;
  const std::string path = dir.write("u.toml", kCamera + kRed +
                                                   "[[spheres]]\ncenter = [0, 0, 0]\n"
                                                   "radious = 1\nmaterial = \"red\"\n");
  const std::string msg = error_of([&] { load_scene(path); });
  expect_message(msg, path, 8, "unknown key 'radious' in spheres[0]");
  EXPECT_TRUE(contains(msg, "did you mean 'radius'?")) << msg;
  EXPECT_TRUE(contains(msg, path + ":8:1:")) << msg;
  expect_scene_errors({
      {kCamera + "[sphere]\nx = 1\n", 4, "unknown key 'sphere'"},
      {kCamera + "fov = 50\n[worlds]\n", 5, "unknown key 'worlds'"},
      {"fov = 50\n" + kCamera, 1, "unknown key 'fov'"},
      {kCamera + "fvo = 50\n", 4, "did you mean 'fov'?"},
      {kCamera + "[materials.m]\ncolor = [1, 0, 0]\n", 5, "unknown key 'color' in materials.m"},
      {kCamera + "[materials.m]\nchecker = { colour = [0, 0, 0] }\n", 5,
       "unknown key 'colour' in materials.m.checker"},
      {kCamera + "[world]\nambiant = [0, 0, 0]\n", 5, "did you mean 'ambient'?"},
      {kCamera + "[[lights]]\nposition = [0, 0, 0]\npower = 3\n", 6,
       "unknown key 'power' in lights[0]"},
      {kCamera + "[[meshes]]\nfile = \"x.obj\"\nrotation = [0, 0, 0]\n", 6,
       "did you mean 'rotate'?"},
      {kCamera + "[[planes]]\nnormal = [0, 1, 0]\ndistance = 0\n", 6,
       "unknown key 'distance' in planes[0]"},
      {kCamera + "\"a\\nb\" = 1\n", 4, "unknown key 'a b'"},  // a newline in a key stays off
  });
}

TEST(SceneIo, WrongTypesAreErrors) {
  expect_scene_errors({
      {kCamera + "fov = \"50\"\n", 4, "camera.fov must be a number (got a string)"},
      {kCamera + "fov = true\n", 4, "camera.fov must be a number (got a boolean)"},
      {kCamera + "up = [0, 1]\n", 4, "camera.up must be an array of 3 numbers (got 2 elements)"},
      {kCamera + "up = [0, 1, 0, 0]\n", 4, "(got 4 elements)"},
      {kCamera + "up = 1\n", 4, "camera.up must be an array of 3 numbers (got an integer)"},
      {kCamera + "up = [0, \"1\", 0]\n", 4, "camera.up[1] must be a number (got a string)"},
      {"camera = 1\n", 1, "camera must be a table (got an integer)"},
      {"spheres = 1\n" + kCamera, 1, "spheres must be an array of tables"},
      {kCamera + "[spheres]\n", 4, "written [[spheres]] (got a table)"},
      {"lights = [1]\n" + kCamera, 1, "lights[0] must be a table (got an integer)"},
      {"materials = [1]\n" + kCamera, 1, "materials must be a table"},
      {"materials.m = 1\n" + kCamera, 1, "materials.m must be a table"},
      {kCamera + kRed + "[[spheres]]\ncenter = [0, 0, 0]\nradius = 1\nmaterial = 3\n", 9,
       "spheres[0].material must be a string (got an integer)"},
      {kCamera + "[[meshes]]\nfile = \"\"\n", 5, "meshes[0].file must not be empty"},
      {kCamera + "[world]\nambient = 1979-05-27\n", 5, "(got a date)"},
  });
}

TEST(SceneIo, NanAndInfinityAreErrorsInEveryNumber) {
  const std::string sphere = "[[spheres]]\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"red\"\n";
  expect_scene_errors({
      {kCamera + "fov = nan\n", 4, "camera.fov must be a finite number (got nan)"},
      {"[camera]\nposition = [0, inf, 0]\nlook_at = [0, 0, 0]\n", 2,
       "camera.position[1] must be a finite number (got inf)"},
      {"[camera]\nposition = [0, 1, 0]\nlook_at = [-inf, 0, 0]\n", 3, "(got -inf)"},
      {kCamera + "up = [0, +nan, 0]\n", 4, "camera.up[1]"},
      {kCamera + "[world]\nambient = [0, nan, 0]\n", 5, "world.ambient[1]"},
      {kCamera + "[world]\nbackground = [inf, 0, 0]\n", 5, "world.background[0]"},
      {kCamera + "[materials.m]\nshininess = inf\n", 5, "materials.m.shininess"},
      {kCamera + "[materials.m]\nior = nan\n", 5, "materials.m.ior"},
      {kCamera + "[materials.m]\ndiffuse = [nan, 0, 0]\n", 5, "materials.m.diffuse[0]"},
      {kCamera + "[materials.m]\nchecker = { scale = inf }\n", 5, "materials.m.checker.scale"},
      {kCamera + "[[lights]]\nposition = [0, 0, 0]\nintensity = nan\n", 6, "lights[0].intensity"},
      {kCamera + kRed + sphere +
           "[[spheres]]\ncenter = [0, 0, 0]\nradius = inf\nmaterial = \"red\"\n",
       12, "spheres[1].radius"},
      {kCamera + kRed + "[[planes]]\nnormal = [0, 1, 0]\noffset = nan\nmaterial = \"red\"\n", 8,
       "planes[0].offset"},
      {kCamera + "[[meshes]]\nfile = \"a.obj\"\nscale = nan\n", 6,
       "meshes[0].scale must be a finite number"},
      {kCamera + "[[meshes]]\nfile = \"a.obj\"\ntranslate = [0, 0, -inf]\n", 6,
       "meshes[0].translate[2]"},
  });
}

TEST(SceneIo, RadiusErrorHasTheDocumentedFormat) {
  TempDir dir;
  const std::string path =
      dir.write("x.toml", kCamera + kRed +
                              "[[spheres]]\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"red\"\n"
                              "[[spheres]]\ncenter = [0, 0, 0]\nradius = -1\nmaterial = \"red\"\n");
  EXPECT_EQ(error_of([&] { load_scene(path); }),
            path + ":12:10: spheres[1].radius must be > 0 (got -1)");
}

TEST(SceneIo, ValuesOutOfRangeAreErrors) {
  const std::string sphere = "[[spheres]]\ncenter = [0, 0, 0]\nmaterial = \"red\"\n";
  expect_scene_errors({
      {kCamera + kRed + sphere + "radius = 0\n", 9, "spheres[0].radius must be > 0 (got 0)"},
      {kCamera + kRed + sphere + "radius = 1e-300\n", 9, "must be > 0 (got 1e-300)"},
      {kCamera + kRed + sphere + "radius = 1e16\n", 9, "spheres[0].radius is too large"},
      {kCamera + "fov = 0\n", 4, "camera.fov must be in (0, 180) (got 0)"},
      {kCamera + "fov = 180\n", 4, "camera.fov must be in (0, 180) (got 180)"},
      {kCamera + "fov = -10\n", 4, "camera.fov must be in (0, 180)"},
      {kCamera + "[materials.m]\nshininess = -1\n", 5,
       "materials.m.shininess must be >= 0 (got -1)"},
      {kCamera + "[materials.m]\nreflectivity = 1.5\n", 5,
       "materials.m.reflectivity must be in [0, 1] (got 1.5)"},
      {kCamera + "[materials.m]\ntransparency = -0.1\n", 5,
       "materials.m.transparency must be in [0, 1]"},
      {kCamera + "[materials.m]\nior = 0\n", 5, "materials.m.ior must be in (0, 100] (got 0)"},
      {kCamera + "[materials.m]\nior = -1.5\n", 5, "materials.m.ior must be in (0, 100]"},
      {kCamera + "[materials.m]\ndiffuse = [0.5, -0.5, 0]\n", 5,
       "materials.m.diffuse[1] must be >= 0"},
      {kCamera + "[materials.m]\nchecker = { scale = 0 }\n", 5,
       "materials.m.checker.scale must be > 0"},
      {kCamera + "[[lights]]\nposition = [0, 0, 0]\nintensity = -1\n", 6,
       "lights[0].intensity must be >= 0"},
      {kCamera + "[[lights]]\nposition = [0, 0, 0]\ncolor = [-1, 0, 0]\n", 6,
       "lights[0].color[0] must be >= 0"},
      {kCamera + "[world]\nambient = [0, 0, -0.2]\n", 5, "world.ambient[2] must be >= 0"},
  });
}

// MTL's Ni is bounded to 100 (rt2/io/mtl.h); a TOML ior the same (1e6 loaded before).
TEST(SceneIo, IorAboveOneHundredIsAnError) {
  expect_scene_errors({
      {kCamera + "[materials.m]\nior = 100.5\n", 5,
       "materials.m.ior must be in (0, 100] (got 100.5)"},
      {kCamera + "[materials.m]\nior = 1e6\n", 5, "materials.m.ior must be in (0, 100]"},
  });
  TempDir dir;
  EXPECT_FLOAT_EQ(material_named(load_text(dir, kCamera + "[materials.m]\nior = 100\n"), "m").ior,
                  100.0f);
}

TEST(SceneIo, ZeroPlaneNormalIsAnError) {
  expect_scene_errors({
      {kCamera + kRed + "[[planes]]\nnormal = [0, 0, 0]\noffset = 1\nmaterial = \"red\"\n", 7,
       "planes[0].normal must not be zero"},
      {kCamera + kRed +
           "[[planes]]\nnormal = [0, 1, 0]\noffset = 1\npoint = [0, 0, 0]\nmaterial = \"red\"\n",
       9, "give offset or point, not both"},
      {kCamera + kRed + "[[planes]]\nnormal = [0, 1, 0]\nmaterial = \"red\"\n", 6,
       "needs offset or point"},
  });
}

TEST(SceneIo, CameraUpThatIsZeroOrParallelToTheViewIsAnError) {
  expect_scene_errors({
      {kCamera + "up = [0, 0, 0]\n", 4, "camera.up must not be zero"},
      {kCamera + "up = [0, 0, 2]\n", 4, "camera.up is parallel to the view direction"},
      {kCamera + "up = [0, 0, -1e-9]\n", 4, "camera.up"},
      {"[camera]\nposition = [0, 5, 0]\nlook_at = [0, 0, 0]\n", 1, "set camera.up"},
  });
}

TEST(SceneIo, LookAtEqualToPositionIsAnError) {
  expect_scene_errors({
      {"[camera]\nposition = [1, 2, 3]\nlook_at = [1, 2, 3]\n", 3,
       "camera.look_at must differ from camera.position"},
      {"[camera]\nposition = [1, 2, 3]\ndirection = [0, 0, 0]\n", 3,
       "camera.direction must not be zero"},
  });
}

TEST(SceneIo, ExactlyOneOfLookAtAndDirectionIsRequired) {
  expect_scene_errors({
      {kCamera + "direction = [0, 0, -1]\n", 4, "give look_at or direction, not both"},
      {"[camera]\nposition = [0, 0, 0]\n", 1, "camera needs look_at or direction"},
  });
}

TEST(SceneIo, UndefinedMaterialIsAnErrorWithASuggestion) {
  TempDir dir;
  const std::string path = dir.write("m.toml", kCamera + kRed +
                                                   "[[spheres]]\ncenter = [0, 0, 0]\n"
                                                   "radius = 1\nmaterial = \"rde\"\n");
  const std::string msg = error_of([&] { load_scene(path); });
  expect_message(msg, path, 9, "spheres[0].material: undefined material 'rde'");
  EXPECT_TRUE(contains(msg, "did you mean 'red'?")) << msg;
  expect_scene_errors({
      {kCamera + "[[planes]]\nnormal = [0, 1, 0]\noffset = 0\nmaterial = \"floor\"\n", 7,
       "undefined material 'floor'"},
      {kCamera + "[[meshes]]\nfile = \"a.obj\"\nmaterial = \"gold\"\n", 6,
       "undefined material 'gold'"},
  });
}

TEST(SceneIo, MissingRequiredKeysAreErrors) {
  expect_scene_errors({
      {"[world]\nambient = [0, 0, 0]\n", 0, "missing required table [camera]"},
      {"[camera]\nlook_at = [0, 0, 0]\n", 1, "camera is missing the required key 'position'"},
      {kCamera + kRed + "[[spheres]]\ncenter = [0, 0, 0]\nmaterial = \"red\"\n", 6,
       "spheres[0] is missing the required key 'radius'"},
      {kCamera + kRed + "[[spheres]]\ncenter = [0, 0, 0]\nradius = 1\n", 6,
       "spheres[0] is missing the required key 'material'"},
      {kCamera + "[[spheres]]\nradius = 1\n", 4, "'center'"},
      {kCamera + "[[lights]]\ncolor = [1, 1, 1]\n", 4,
       "lights[0] is missing the required key 'position'"},
      {kCamera + kRed + "[[planes]]\noffset = 0\nmaterial = \"red\"\n", 6, "'normal'"},
      {kCamera + "[[meshes]]\nscale = 2\n", 4, "meshes[0] is missing the required key 'file'"},
  });
}

TEST(SceneIo, ZeroOrNonFiniteScaleIsAnError) {
  expect_scene_errors({
      {kCamera + "[[meshes]]\nfile = \"a.obj\"\nscale = 0\n", 6,
       "meshes[0].scale must not be zero"},
      {kCamera + "[[meshes]]\nfile = \"a.obj\"\nscale = [1, 0, 1]\n", 6,
       "meshes[0].scale[1] must not be zero"},
      {kCamera + "[[meshes]]\nfile = \"a.obj\"\nscale = inf\n", 6,
       "meshes[0].scale must be a finite number"},
      {kCamera + "[[meshes]]\nfile = \"a.obj\"\nscale = [1, 1, nan]\n", 6, "meshes[0].scale[2]"},
      {kCamera + "[[meshes]]\nfile = \"a.obj\"\nscale = 1e20\n", 6, "meshes[0].scale is too large"},
      {kCamera + "[[meshes]]\nfile = \"a.obj\"\nscale = \"big\"\n", 6,
       "meshes[0].scale must be a number"},
  });
}

TEST(SceneIo, ATransformThatFlattensTheMeshIsAnError) {
  TempDir dir;
  dir.write("tri.obj", kTriangleObj);
  const std::string path =
      dir.write("t.toml", kCamera + "[[meshes]]\nfile = \"tri.obj\"\nscale = 1e-30\n");
  expect_message(error_of([&] { load_scene(path); }), path, 4, "degenerate after the transform");
}

// ---- OBJ errors -------------------------------------------------------------------------

TEST(SceneIo, MissingObjNamesTheSceneLineAndThePath) {
  TempDir dir;
  const std::string path =
      dir.write("s.toml", kCamera + "[[meshes]]\nfile = \"models/chair.obj\"\n");
  const std::string msg = error_of([&] { load_scene(path); });
  expect_message(msg, path, 5, "meshes[0].file");
  EXPECT_TRUE(contains(msg, dir.path("models/chair.obj"))) << msg;
  EXPECT_TRUE(contains(msg, "not found")) << msg;
}

// Loads `obj` as a mesh of a scene and expects an error at line `line` of the OBJ.
void expect_obj_error(std::string_view obj, int line, std::string_view text) {
  TempDir dir;
  const std::string obj_path = dir.write("mesh.obj", obj);
  const std::string scene = dir.write("s.toml", kCamera + "[[meshes]]\nfile = \"mesh.obj\"\n");
  SCOPED_TRACE(obj);
  expect_message(error_of([&] { load_scene(scene); }), obj_path, line, text);
  Scene s;
  expect_message(error_of([&] { load_obj(obj_path, s); }), obj_path, line, text);
}

TEST(SceneIo, FaceIndexOutOfRangeNamesTheObjLine) {
  expect_obj_error("# tri\nv 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 3\nf 1 2 9\n", 7,
                   "face references vertex 9, but only 3 vertices are defined");
  expect_obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 4\n", 4, "face references vertex 4");
  expect_obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", 4,
                   "face references vertex -4 (relative)");
  expect_obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n", 4, "is not an index");
  expect_obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//2\n", 5,
                   "face references normal 2, but only 1 normal is defined");
  expect_obj_error("v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\nf 3 2 5\r\n", 5, "vertex 5");
  expect_obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", 4, "at least 3");
  expect_obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", 4, "'x' is not an index");
}

TEST(SceneIo, FaceIndexZeroIsAnError) {
  expect_obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", 4,
                   "face references vertex 0, but OBJ indices start at 1");
  expect_obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/0 2/1 3/1\n", 5, "texture coordinate 0");
}

TEST(SceneIo, NonFiniteVertexNamesTheObjLine) {
  expect_obj_error("v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n", 2, "vertex is not finite");
  expect_obj_error("v 0 0 0\nv 1 0 0\n# comment\nv 0 1 -inf\nf 1 2 3\n", 4, "vertex is not finite");
  expect_obj_error("v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n", 2,
                   "vertex is not finite");  // beyond float
  expect_obj_error("v 0 0 0\nv 1 zero 0\nv 0 1 0\nf 1 2 3\n", 2, "'zero' is not a number");
  expect_obj_error("v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n", 2, "vertex needs 3 coordinates");
}

TEST(SceneIo, ObjWithoutFacesIsAnError) {
  expect_obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\n", 0, "no faces");
  expect_obj_error("", 0, "no faces");
  expect_obj_error("v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n", 0, "degenerate");
}

TEST(SceneIo, CoordinatesTooLargeOrSmallForFloatAreasAreNamed) {
  // Not "all faces are degenerate": the triangles are fine, a float cannot hold their areas.
  expect_obj_error("v 0 0 0\nv 1e37 0 0\nv 0 1e37 0\nf 1 2 3\n", 0,
                   "all 1 faces are degenerate: the coordinates are too large for float "
                   "arithmetic: the triangle areas overflow (the mesh spans 1.4142135");
  expect_obj_error("v 0 0 0\nv 1e-30 0 0\nv 0 1e-30 0\nf 1 2 3\nf 1 3 2\n", 0,
                   "all 2 faces are degenerate: the coordinates are too small for float "
                   "arithmetic: the triangle areas underflow to 0");
  expect_obj_error("v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n", 0,
                   "all 1 faces are degenerate (zero or non-finite area)");
}

TEST(SceneIo, TinyobjloaderErrorsAreReportedOnOneLine) {
  // tinyobjloader itself rejects index 0 in a line element.
  expect_obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nl 0 1\nf 1 2 3\n", 0, "tinyobjloader");
}

TEST(SceneIo, FailedLoadObjLeavesTheSceneUnchanged) {
  TempDir dir;
  dir.write("f.mtl", "newmtl a\nKd 1 0 0\n");
  const std::string obj = dir.write("f.obj",
                                    "mtllib f.mtl\nv 0 0 0\nv 1 0 0\nv 2 0 0\n"
                                    "usemtl a\nf 1 2 3\n");  // only a degenerate face
  Scene s;
  s.add_material("mine", Material{});
  s.degenerate_triangles = 5;
  expect_message(error_of([&] { load_obj(obj, s); }), obj, 0, "degenerate");
  EXPECT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.material_names.size(), 1u);
  EXPECT_EQ(s.degenerate_triangles, 5u);
}

TEST(SceneIo, BinaryObjIsAnErrorNotACrash) {
  std::string junk;
  std::mt19937 random(7);
  for (int i = 0; i < 20000; ++i) junk += static_cast<char>(random() % 256);
  TempDir dir;
  const std::string path = dir.write("junk.obj", junk);
  Scene s;
  const std::string msg = error_of([&] { load_obj(path, s); });
  expect_message(msg, path, 0, "");
}

// Refused at once, saying what the file is (as TOML scenes are), not as a first bad line.
TEST(SceneIo, CompressedUtf16OrBinaryObjIsRefusedSayingWhatItIs) {
  const std::string gzip("\x1F\x8B\x08\x00\x00\x00\x00\x00\x00\x03+S0T0U0\xE2\x02\x00", 19);
  const std::string utf16_le = [] {
    std::string u("\xFF\xFE", 2);
    for (const char c : kTriangleObj) u += std::string{c, '\0'};
    return u;
  }();
  for (const auto& [bytes, line, text] : std::vector<std::tuple<std::string, int, std::string>>{
           {gzip, 0, "file is gzip-compressed; decompress it first (gunzip)"},
           {std::string("PK\x03\x04\x14\x00", 6), 0, "file is a ZIP archive"},
           {utf16_le, 0,
            "file is UTF-16 (it starts with a UTF-16 byte-order mark); save it as UTF-8"},
           {utf16_le.substr(2), 1, "file contains a NUL byte: it is binary or UTF-16"},
           {kTriangleObj + "v 1 1 0\n" + std::string(1, '\0') + "\n", 6, "NUL byte"},
       }) {
    TempDir dir;
    const std::string path = dir.write("m.obj", bytes);
    Scene s;
    expect_message(error_of([&] { load_obj(path, s); }), path, line, text);
  }
  // The same for an MTL library, named in the message.
  TempDir dir;
  const std::string mtl = dir.write("t.mtl", gzip);
  const std::string obj = dir.write("t.obj", "mtllib t.mtl\nusemtl m\n" + kTriangleObj);
  Scene s;
  expect_message(error_of([&] { load_obj(obj, s); }), mtl, 0, "gzip-compressed");
}

// The bytes this process has read through read() so far (/proc/self/io's rchar).
std::uint64_t bytes_read() {
  std::ifstream io("/proc/self/io");
  std::string key;
  std::uint64_t value = 0;
  while (io >> key >> value)
    if (key == "rchar:") return value;
  return 0;
}

// A sparse file made with truncate: 2 GiB of zero bytes (the limit is 4 GiB) is refused after
// its first block, not read whole into memory first.
TEST(SceneIo, TwoGigabytesOfZeroBytesAreRefusedAfterTheFirstBlock) {
  TempDir dir;
  const std::string path = dir.path("zeros.obj");
  std::ofstream(path).close();
  fs::resize_file(path, std::uintmax_t{2} << 30);
  Scene s;
  const std::uint64_t before = bytes_read();
  expect_message(error_of([&] { load_obj(path, s); }), path, 1, "file contains a NUL byte");
  const std::uint64_t read = bytes_read() - before;
  std::printf("[ measure  ] 2 GiB of zeros refused after reading %llu bytes\n",
              static_cast<unsigned long long>(read));
  EXPECT_LT(read, std::uint64_t(1) << 20);  // one block of 64 KiB, not the 2 GiB
}

TEST(SceneIo, BadKrInMtlNamesTheMtlLine) {
  TempDir dir;
  const std::string mtl = dir.write("k.mtl", "newmtl a\nKd 1 1 1\nKr shiny\n");
  const std::string obj =
      dir.write("k.obj", "mtllib k.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n");
  Scene s;
  expect_message(error_of([&] { load_obj(obj, s); }), mtl, 3, "Kr must be a number");
}

// ---- files an OBJ or MTL names ----------------------------------------------------------

const std::string kQuad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

// One face per material of `materials` (m0, m1, ...), the OBJ naming `mtllib`.
std::string obj_using(const std::string& mtllib, int materials) {
  std::string obj = "mtllib " + mtllib + "\n" + kQuad;
  for (int i = 0; i < materials; ++i) obj += "usemtl m" + std::to_string(i) + "\nf 1 2 3\n";
  return obj;
}

// The file of the texture of material `name` of `s`, or "" without one.
std::string texture_of(const Scene& s, const std::string& name) {
  const std::uint32_t t = material_named(s, name).base_color_texture;
  return t == kNoTexture ? "" : s.textures.at(t).path;
}

bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;
  return fs::equivalent(a, b, ec);
}

TEST(SceneIo, MtlTexturePathsWrittenOnWindowsResolveBesideTheMtl) {
  TempDir dir;
  const std::string tex = dir.write("a/tex.jpg", "x"), wood = dir.write("a/textures/wood.png", "x");
  dir.write("a/m.mtl",
            "newmtl m0\nmap_Kd .\\tex.jpg\n"                      // backslash, from .
            "newmtl m1\nmap_Kd textures\\wood.png\n"              // a relative folder
            "newmtl m2\nmap_Kd C:\\Users\\me\\Desktop\\tex.jpg\n"  // a drive: beside the MTL
            "newmtl m3\nmap_Kd \\\\server\\share\\tex.jpg\n"      // a share: beside the MTL
            "newmtl m4\nmap_Kd -s 1 1 1 .\\textures\\.\\wood.png\n");
  testing::internal::CaptureStderr();
  const Scene s = load_scene(dir.write("a/t.obj", obj_using("m.mtl", 5)));
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  EXPECT_TRUE(same_file(texture_of(s, "t.obj:m0"), tex));
  EXPECT_TRUE(same_file(texture_of(s, "t.obj:m1"), wood));
  EXPECT_TRUE(same_file(texture_of(s, "t.obj:m2"), tex));
  EXPECT_TRUE(same_file(texture_of(s, "t.obj:m3"), tex));
  EXPECT_TRUE(same_file(texture_of(s, "t.obj:m4"), wood));
}

TEST(SceneIo, MtlTextureNamesMatchIgnoringCaseWhenOneFileMatches) {
  TempDir dir;
  const std::string wood = dir.write("Textures/Wood.PNG", "x");
  dir.write("Textures/Pine.png", "x");
  dir.write("Textures/PINE.PNG", "x");
  dir.write("m.mtl", "newmtl m0\nmap_Kd textures\\wood.png\nnewmtl m1\nmap_Kd TEXTURES/pine.png\n");
  testing::internal::CaptureStderr();
  const Scene s = load_scene(dir.write("t.obj", obj_using("m.mtl", 2)));
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_TRUE(same_file(texture_of(s, "t.obj:m0"), wood));
  EXPECT_EQ(texture_of(s, "t.obj:m1"), "");  // Pine.png or PINE.PNG: neither is taken
  EXPECT_TRUE(contains(err, "m.mtl:4: texture 'TEXTURES/pine.png' not found")) << err;
}

TEST(SceneIo, MtllibNamesWrittenOnWindowsResolveBesideTheObj) {
  TempDir dir;
  dir.write("a/materials/M.mtl", "newmtl m0\nKd 0.25 0.5 0.75\n");
  for (const std::string lib : {"materials\\M.mtl", ".\\Materials\\m.MTL", "D:\\work\\M.mtl"}) {
    SCOPED_TRACE(lib);
    if (lib.starts_with("D:")) dir.write("a/M.mtl", "newmtl m0\nKd 0.25 0.5 0.75\n");
    testing::internal::CaptureStderr();
    const Scene s = load_scene(dir.write("a/t.obj", obj_using(lib, 1)));
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
    expect_vec(material_named(s, "t.obj:m0").diffuse, 0.25f, 0.5f, 0.75f);
  }
}

TEST(SceneIo, MtlTextureOutsideTheObjFolderIsRefusedUnlessAllowed) {
  TempDir dir;
  const std::string secret = dir.write("outside/secret.png", "x");
  const std::string mtl = dir.write("asset/x.mtl", "newmtl m0\nKd 1 1 1\nmap_Kd ../outside/secret.png\n");
  const std::string obj = dir.write("asset/x.obj", obj_using("x.mtl", 1));
  EXPECT_EQ(error_of([&] { load_scene(obj); }),
            mtl + ":3: map_Kd '../outside/secret.png' lies outside the asset's folder "
                  "(--allow-outside-assets reads it)");
  // Missing or absolute, written with backslashes or not: the same.
  for (const std::string& name : {std::string("..\\outside\\gone.png"), secret}) {
    dir.write("asset/x.mtl", "newmtl m0\nnorm " + name + "\nPr 1\n");
    expect_message(error_of([&] { load_scene(obj); }), mtl, 2,
                   "norm '" + name + "' lies outside the asset's folder");
  }
  dir.write("asset/x.mtl", "newmtl m0\nKd 1 1 1\nmap_Kd ../outside/secret.png\n");
  const Scene s = load_scene(obj, AssetPolicy{.allow_outside_assets = true});
  EXPECT_TRUE(same_file(texture_of(s, "x.obj:m0"), secret));
}

TEST(SceneIo, MtllibOutsideTheObjFolderIsRefusedUnlessAllowed) {
  TempDir dir;
  const std::string lib = dir.write("shared/m.mtl", "newmtl m0\nKd 0.5\n");
  for (const std::string& name : {std::string("../shared/m.mtl"), lib, std::string("../none.mtl")}) {
    SCOPED_TRACE(name);
    const std::string obj = dir.write("asset/x.obj", "# a comment\n" + obj_using(name, 1));
    expect_message(error_of([&] { load_scene(obj); }), obj, 2,
                   "mtllib '" + name + "' lies outside the asset's folder "
                   "(--allow-outside-assets reads it)");
  }
  const std::string obj = dir.write("asset/x.obj", obj_using("../shared/m.mtl", 1));
  const Scene s = load_scene(obj, AssetPolicy{.allow_outside_assets = true});
  expect_vec(material_named(s, "x.obj:m0").diffuse, 0.5f, 0.5f, 0.5f);
}

TEST(SceneIo, SymbolicLinksOutOfTheObjFolderAreRefusedAndThoseWithinFollowed) {
  TempDir dir;
  dir.write("outside/secret.png", "x");
  dir.write("outside/m.mtl", "newmtl m0\nKd 0.5\n");
  const std::string inside = dir.write("asset/real/tex.png", "x");
  fs::create_symlink(dir.root() / "outside/secret.png", dir.root() / "asset/leak.png");
  fs::create_symlink(dir.root() / "outside", dir.root() / "asset/linked");
  fs::create_symlink("real", dir.root() / "asset/alias");
  const std::string mtl = dir.write("asset/x.mtl", "newmtl m0\nmap_Kd leak.png\n");
  const std::string obj = dir.write("asset/x.obj", obj_using("x.mtl", 1));
  expect_message(error_of([&] { load_scene(obj); }), mtl, 2,
                 "map_Kd 'leak.png' lies outside the asset's folder");
  dir.write("asset/x.mtl", "newmtl m0\nmap_Kd LINKED/secret.png\n");  // found ignoring case
  expect_message(error_of([&] { load_scene(obj); }), mtl, 2,
                 "map_Kd 'LINKED/secret.png' lies outside the asset's folder");
  const std::string via_link = dir.write("asset/v.obj", obj_using("linked/m.mtl", 1));
  expect_message(error_of([&] { load_scene(via_link); }), via_link, 1,
                 "mtllib 'linked/m.mtl' lies outside the asset's folder");
  dir.write("asset/x.mtl", "newmtl m0\nmap_Kd alias/../alias/tex.png\n");
  EXPECT_TRUE(same_file(texture_of(load_scene(obj), "x.obj:m0"), inside));
}

TEST(SceneIo, AFolderWhoseNameExtendsTheObjFolderIsOutsideIt) {
  TempDir dir;
  dir.write("assets/t.png", "x");
  const std::string mtl = dir.write("asset/x.mtl", "newmtl m0\nmap_Kd ../assets/t.png\n");
  const std::string obj = dir.write("asset/x.obj", obj_using("x.mtl", 1));
  expect_message(error_of([&] { load_scene(obj); }), mtl, 2, "lies outside the asset's folder");
}

TEST(SceneIo, DevicesNamedByAnObjOrMtlStayRefusedWithAWarning) {
  TempDir dir;
  dir.write("x.mtl", "newmtl m0\nKd 0.5\nmap_Kd /dev/zero\n");
  testing::internal::CaptureStderr();
  const Scene s = load_scene(dir.write("x.obj", obj_using("x.mtl", 1) + "mtllib /dev/null\n"));
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_TRUE(contains(err, "texture '/dev/zero' is not a regular file; ignored")) << err;
  EXPECT_TRUE(contains(err, "material library '/dev/null' is not a regular file")) << err;
  EXPECT_TRUE(s.textures.empty());
}

TEST(SceneIo, AnObjOfATomlSceneMayLieAnywhereButItsOwnFilesLieInItsFolder) {
  TempDir dir;
  dir.write("elsewhere/ok.mtl", "newmtl m0\nKd 0.5\n");
  dir.write("elsewhere/ok.obj", obj_using("ok.mtl", 1));
  dir.write("shared.mtl", "newmtl m0\nKd 0.5\n");
  dir.write("elsewhere/bad.obj", obj_using("../shared.mtl", 1));
  const Scene s = load_scene(
      dir.write("scenes/s.toml", kCamera + "[[meshes]]\nfile = \"../elsewhere/ok.obj\"\n"));
  EXPECT_EQ(s.meshes.size(), 1u);
  expect_message(error_of([&] {
                   load_scene(dir.write("scenes/t.toml",
                                        kCamera + "[[meshes]]\nfile = \"../elsewhere/bad.obj\"\n"));
                 }),
                 dir.path("scenes") + "/../elsewhere/bad.obj", 1,
                 "mtllib '../shared.mtl' lies outside the asset's folder");
}

TEST(SceneIo, AMissingMeshUnderDataMeshesSaysWhichScriptFetchesIt) {
  TempDir dir;
  const std::string fetched =
      dir.write("scenes/s.toml", kCamera + "[[meshes]]\nfile = \"../data/meshes/gone.obj\"\n");
  const std::string msg = error_of([&] { load_scene(fetched); });
  expect_message(msg, fetched, 5, "meshes[0].file");
  EXPECT_TRUE(contains(msg, "data/meshes/gone.obj': file not found (scripts/fetch-meshes"))
      << msg;
  const std::string other =
      dir.write("scenes/o.toml", kCamera + "[[meshes]]\nfile = \"../meshes/gone.obj\"\n");
  EXPECT_FALSE(contains(error_of([&] { load_scene(other); }), "fetch-meshes"));
}

// scenes/hall.toml in a tree without data/: the dragon's message names the script.
TEST(SceneIo, TheHallWithoutFetchedMeshesSaysWhichScriptFetchesTheDragon) {
  TempDir dir;
  fs::create_directories(dir.root() / "scenes");
  for (const char* name : {"hall.toml", "hall_pillars.obj"})
    fs::copy_file(source_file(std::string("scenes/") + name), dir.root() / "scenes" / name,
                  fs::copy_options::none);
  const std::string msg = error_of([&] { load_scene(dir.path("scenes/hall.toml")); });
  EXPECT_TRUE(contains(msg, "data/meshes/ChineseDragon-10kv.obj': file not found "
                            "(scripts/fetch-meshes"))
      << msg;
}

}  // namespace
}  // namespace rt2
