// Physically based materials and environments in scene files: TOML's model = "pbr" and
// [environment] (rt2/io/toml_scene.cpp) and MTL's PBR statements (rt2/io/mtl.cpp), read into
// Material, TextureDesc and EnvironmentDesc, and their errors, each one line starting with
// "file:line:".
#include <gtest/gtest.h>

#include <string>
#include <string_view>

#include "rt2/io/scene_io.h"
#include "tests/rt2/error_of.h"
#include "tests/rt2/temp_dir.h"

namespace rt2 {
namespace {

using test::error_of;
using test::TempDir;

// Three lines, so that what follows starts at line 4.
const std::string kCam = "[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\n";

const Material& named(const Scene& s, const std::string& name) {
  const int i = s.find_material(name);
  EXPECT_GE(i, 0) << name;
  return s.materials.at(static_cast<std::size_t>(i < 0 ? 0 : i));
}

void expect_rgb(const vec4& v, float r, float g, float b) {
  EXPECT_FLOAT_EQ(v[0], r);
  EXPECT_FLOAT_EQ(v[1], g);
  EXPECT_FLOAT_EQ(v[2], b);
}

// Loading the scene `toml` fails with one line starting "scene.toml:LINE:" and saying every
// one of `says`.
void expect_toml_error(std::string_view toml, int line,
                       std::initializer_list<std::string_view> says) {
  const TempDir dir("pbr_scene");
  const std::string path = dir.write("scene.toml", toml);
  const std::string msg = error_of([&] { load_scene(path); });
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  const std::string where = path + ":" + std::to_string(line) + ":";
  EXPECT_EQ(msg.rfind(where, 0), 0u) << "expected to start with " << where << ": " << msg;
  for (const std::string_view s : says)
    EXPECT_NE(msg.find(s), std::string::npos) << "expected '" << s << "' in: " << msg;
}

TEST(PbrSceneIo, EveryPbrKeyIsReadIntoTheMaterial) {
  const TempDir dir("pbr_scene");
  for (const char* f : {"c.png", "mr.png", "n.png"}) dir.write(f, "only opened when compiled");
  const Scene s = load_scene(dir.write("scene.toml", kCam + R"(
[materials.gold]
model = "pbr"
base_color = [1, 0.8, 0.3]
metallic = 0.9
roughness = 0.25
emissive = [0.1, 0.2, 3]
transmission = 0.5
ior = 1.33
normal_scale = 0.5
base_color_texture = "c.png"
metallic_roughness_texture = "mr.png"
normal_texture = "n.png"
emissive_texture = "c.png"
[materials.other]
model = "pbr"
base_color_texture = "c.png"
metallic_roughness_texture = "c.png"
normal_texture = "mr.png"
[materials.plain]
model = "pbr"
)"));
  const Material& m = named(s, "gold");
  EXPECT_EQ(m.model, Shading::pbr);
  expect_rgb(m.base_color, 1.0f, 0.8f, 0.3f);
  EXPECT_FLOAT_EQ(m.metallic, 0.9f);
  EXPECT_FLOAT_EQ(m.roughness, 0.25f);
  expect_rgb(m.emissive, 0.1f, 0.2f, 3.0f);
  EXPECT_FLOAT_EQ(m.transmission, 0.5f);
  EXPECT_FLOAT_EQ(m.ior, 1.33f);
  EXPECT_FLOAT_EQ(m.normal_scale, 0.5f);
  // the textures: one per file and colour space, colours sRGB, data linear
  ASSERT_EQ(s.textures.size(), 4u);
  const auto texture = [&](std::uint32_t i) -> const TextureDesc& { return s.textures.at(i); };
  EXPECT_EQ(texture(m.base_color_texture).path, dir.path("c.png"));
  EXPECT_TRUE(texture(m.base_color_texture).srgb);
  EXPECT_EQ(m.emissive_texture, m.base_color_texture);
  EXPECT_EQ(texture(m.metallic_roughness_texture).path, dir.path("mr.png"));
  EXPECT_FALSE(texture(m.metallic_roughness_texture).srgb);
  EXPECT_EQ(texture(m.normal_texture).path, dir.path("n.png"));
  EXPECT_FALSE(texture(m.normal_texture).srgb);
  EXPECT_TRUE(texture(m.base_color_texture).data.empty());
  const Material& o = named(s, "other");
  EXPECT_EQ(o.base_color_texture, m.base_color_texture);
  EXPECT_EQ(o.normal_texture, m.metallic_roughness_texture);
  EXPECT_NE(o.metallic_roughness_texture, m.base_color_texture);  // same file, linear
  EXPECT_EQ(texture(o.metallic_roughness_texture).path, dir.path("c.png"));
  EXPECT_FALSE(texture(o.metallic_roughness_texture).srgb);
  // the defaults: glTF's
  const Material& p = named(s, "plain");
  EXPECT_EQ(p.model, Shading::pbr);
  expect_rgb(p.base_color, 1.0f, 1.0f, 1.0f);
  EXPECT_EQ(p.metallic, 0.0f);
  EXPECT_EQ(p.roughness, 1.0f);
  expect_rgb(p.emissive, 0.0f, 0.0f, 0.0f);
  EXPECT_EQ(p.transmission, 0.0f);
  EXPECT_EQ(p.normal_scale, 1.0f);
  EXPECT_EQ(p.base_color_texture, kNoTexture);
  EXPECT_EQ(p.normal_texture, kNoTexture);
}

TEST(PbrSceneIo, PhongIsTheDefaultModelAndDiffuseTextureIsItsSrgbColourTexture) {
  const TempDir dir("pbr_scene");
  dir.write("wood.png", "x");
  const Scene s = load_scene(dir.write("scene.toml", kCam + R"(
[materials.a]
diffuse = [0.5, 0.5, 0.5]
[materials.b]
model = "phong"
diffuse_texture = "wood.png"
)"));
  EXPECT_EQ(named(s, "a").model, Shading::phong);
  EXPECT_EQ(named(s, "a").base_color_texture, kNoTexture);
  const Material& b = named(s, "b");
  EXPECT_EQ(b.model, Shading::phong);
  ASSERT_EQ(b.base_color_texture, 0u);
  EXPECT_EQ(s.textures.at(0).path, dir.path("wood.png"));
  EXPECT_TRUE(s.textures.at(0).srgb);
}

TEST(PbrSceneIo, APhongKeyInAPbrMaterialIsAnErrorNamingItsLine) {
  expect_toml_error(kCam + "[materials.m]\nmodel = \"pbr\"\nshininess = 10\n", 6,
                    {"shininess", "materials.m"});
}

TEST(PbrSceneIo, APbrKeyInAPhongMaterialIsAnErrorNamingItsLine) {
  expect_toml_error(kCam + "[materials.m]\ndiffuse = [1, 1, 1]\nmetallic = 1\n", 6,
                    {"metallic", "materials.m"});
  expect_toml_error(kCam + "[materials.m]\nmodel = \"phong\"\nbase_color_texture = \"x.png\"\n",
                    6, {"base_color_texture"});
}

TEST(PbrSceneIo, AnUnknownModelIsAnError) {
  expect_toml_error(kCam + "[materials.m]\nmodel = \"blinn\"\n", 5,
                    {"materials.m.model", "\"phong\" or \"pbr\""});
}

TEST(PbrSceneIo, PbrNumbersOutOfRangeAreErrorsGivingTheRange) {
  expect_toml_error(kCam + "[materials.m]\nmodel = \"pbr\"\nmetallic = 1.5\n", 6,
                    {"materials.m.metallic", "[0, 1]"});
  expect_toml_error(kCam + "[materials.m]\nmodel = \"pbr\"\nroughness = -0.1\n", 6,
                    {"materials.m.roughness", "[0, 1]"});
  expect_toml_error(kCam + "[materials.m]\nmodel = \"pbr\"\ntransmission = 2\n", 6,
                    {"materials.m.transmission"});
  expect_toml_error(kCam + "[materials.m]\nmodel = \"pbr\"\nemissive = [0, -1, 0]\n", 6,
                    {"materials.m.emissive"});
}

TEST(PbrSceneIo, AMissingTextureFileIsAnErrorNamingItsLineAndPath) {
  const TempDir dir("pbr_scene");
  const std::string path = dir.write(
      "scene.toml", kCam + "[materials.m]\nmodel = \"pbr\"\n\nnormal_texture = \"tex/none.png\"\n");
  const std::string msg = error_of([&] { load_scene(path); });
  EXPECT_EQ(msg.rfind(path + ":7:", 0), 0u) << msg;
  EXPECT_NE(msg.find(dir.path("tex/none.png")), std::string::npos) << msg;
  EXPECT_NE(msg.find("normal_texture"), std::string::npos) << msg;
  // a folder is not a texture either
  expect_toml_error(kCam + "[materials.m]\ndiffuse_texture = \".\"\n", 5,
                    {"diffuse_texture", "not a regular file"});
}

TEST(PbrSceneIo, EnvironmentKeysAreReadWithTheImageRelativeToTheSceneFolder) {
  const TempDir dir("pbr_scene");
  dir.write("sky/studio.exr", "only read when compiled");
  const Scene s = load_scene(dir.write("scene.toml", kCam + R"(
[environment]
image = "sky/studio.exr"
intensity = 2.5
rotation = 90
sun_direction = [0, 1, 0]
)"));
  ASSERT_TRUE(s.environment.has_value());
  EXPECT_EQ(s.environment->image, dir.path("sky/studio.exr"));
  EXPECT_FLOAT_EQ(s.environment->intensity, 2.5f);
  EXPECT_FLOAT_EQ(s.environment->rotation_degrees, 90.0f);
  expect_rgb(s.environment->sun_direction, 0.0f, 1.0f, 0.0f);
}

TEST(PbrSceneIo, AnEnvironmentWithoutAnImageIsTheProceduralSkyAndNoneIsNoEnvironment) {
  const TempDir dir("pbr_scene");
  const Scene sky = load_scene(dir.write("sky.toml", kCam + "[environment]\nintensity = 0.5\n"));
  ASSERT_TRUE(sky.environment.has_value());
  EXPECT_TRUE(sky.environment->image.empty());
  EXPECT_FLOAT_EQ(sky.environment->intensity, 0.5f);
  EXPECT_FALSE(load_scene(dir.write("none.toml", kCam)).environment.has_value());
}

TEST(PbrSceneIo, EnvironmentErrorsNameTheirLine) {
  expect_toml_error(kCam + "[environment]\nsun_direction = [0, 0, 0]\n", 5,
                    {"sun_direction must not be zero"});
  expect_toml_error(kCam + "[environment]\n\nimage = \"nowhere.hdr\"\n", 6,
                    {"environment.image", "nowhere.hdr"});
  expect_toml_error(kCam + "[environment]\nintensity = -1\n", 5, {"environment.intensity"});
  expect_toml_error(kCam + "[environment]\nrotaton = 90\n", 5, {"rotaton", "rotation"});
}

// ---- MTL ----------------------------------------------------------------------------------

// An OBJ triangle using the material of the MTL text `mtl` (as "newmtl m"), loaded.
Scene load_mtl(const TempDir& dir, const std::string& mtl) {
  dir.write("t.mtl", "newmtl m\n" + mtl);
  Scene s;
  load_obj(dir.write("t.obj", "mtllib t.mtl\nusemtl m\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), s);
  return s;
}

TEST(PbrMtl, PrPmAndKeMakeAPbrMaterialWithThoseValues) {
  const TempDir dir("pbr_mtl");
  const Scene s = load_mtl(dir, "Kd 0.8 0.6 0.4\nPr 0.3\nPm 0.7\nKe 0.1 0.2 0.3\nNi 1.6\n");
  const Material& m = named(s, "t.obj:m");
  EXPECT_EQ(m.model, Shading::pbr);
  expect_rgb(m.base_color, 0.8f, 0.6f, 0.4f);
  EXPECT_FLOAT_EQ(m.roughness, 0.3f);
  EXPECT_FLOAT_EQ(m.metallic, 0.7f);
  expect_rgb(m.emissive, 0.1f, 0.2f, 0.3f);
  EXPECT_FLOAT_EQ(m.ior, 1.6f);
  EXPECT_EQ(m.transmission, 0.0f);
  // either of Pr and Pm alone is enough
  EXPECT_EQ(named(load_mtl(dir, "Pm 1\n"), "t.obj:m").model, Shading::pbr);
  EXPECT_EQ(named(load_mtl(dir, "Pr 0.5\n"), "t.obj:m").model, Shading::pbr);
}

TEST(PbrMtl, RoughnessMetallicAndNormalMapsAreLinearTextures) {
  const TempDir dir("pbr_mtl");
  for (const char* f : {"r.png", "m.png", "n.png", "c.png"}) dir.write(f, "x");
  const Scene s = load_mtl(
      dir, "Kd 1 1 1\nmap_Kd c.png\nmap_Pr r.png\nmap_Pm m.png\nnorm -bm 0.5 n.png\n");
  const Material& m = named(s, "t.obj:m");
  EXPECT_EQ(m.model, Shading::pbr);  // map_Pr alone makes it physically based
  ASSERT_EQ(s.textures.size(), 4u);
  const auto expect_texture = [&](std::uint32_t i, const char* file, bool srgb) {
    ASSERT_LT(i, s.textures.size()) << file;
    EXPECT_EQ(s.textures[i].path, dir.path(file));
    EXPECT_EQ(s.textures[i].srgb, srgb) << file;
  };
  expect_texture(m.base_color_texture, "c.png", true);
  expect_texture(m.roughness_texture, "r.png", false);
  expect_texture(m.metallic_texture, "m.png", false);
  expect_texture(m.normal_texture, "n.png", false);
  EXPECT_FLOAT_EQ(m.normal_scale, 0.5f);
  EXPECT_EQ(m.metallic_roughness_texture, kNoTexture);
  // without -bm the scale is 1
  EXPECT_FLOAT_EQ(named(load_mtl(dir, "Pr 1\nnorm n.png\n"), "t.obj:m").normal_scale, 1.0f);
}

TEST(PbrMtl, DissolveOnAPbrMaterialIsTransmission) {
  const TempDir dir("pbr_mtl");
  const Material m = named(load_mtl(dir, "Pr 0.1\nd 0.25\n"), "t.obj:m");
  EXPECT_EQ(m.model, Shading::pbr);
  EXPECT_FLOAT_EQ(m.transmission, 0.75f);
  EXPECT_FLOAT_EQ(named(load_mtl(dir, "Pr 0.1\nTr 0.4\n"), "t.obj:m").transmission, 0.4f);
}

TEST(PbrMtl, AMaterialWithOnlyKdAndKsStaysPhong) {
  const TempDir dir("pbr_mtl");
  const Material m = named(load_mtl(dir, "Kd 0.5 0.4 0.3\nKs 0.2\nNs 20\n"), "t.obj:m");
  EXPECT_EQ(m.model, Shading::phong);
  expect_rgb(m.diffuse, 0.5f, 0.4f, 0.3f);
  expect_rgb(m.specular, 0.2f, 0.2f, 0.2f);
}

}  // namespace
}  // namespace rt2
