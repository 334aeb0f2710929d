// Textures and environments in rendered images: scene files written into a temporary folder
// with their images (write_image), loaded by load_scene and rendered by the kernel. Each
// check is a property of the picture (which colour shows where, what changes it and what
// does not), not a stored image.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "rt2/image/image_io.h"
#include "rt2/io/scene_io.h"
#include "rt2/image/srgb.h"
#include "tests/rt2/temp_dir.h"
#include "tests/rt2/test_util.h"

namespace rt2 {
namespace {

using test::TempDir;

constexpr int kSize = 32;

RenderSettings settings() {
  RenderSettings st;
  st.width = st.height = kSize;
  st.depth = 1;
  return st;
}

Image render_file(const std::string& path) { return test::render_scene(load_scene(path), settings()); }

const float* pixel(const Image& img, int x, int y) { return img.pixel(x, y); }

// A w x h image whose texel (x, y) is colour(x, y) as 8-bit sRGB values, written exactly
// (each value is decoded so that write_image's encoding gives it back).
template <class F>
void write_texels(const std::string& path, int w, int h, F colour) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::array<int, 3> c = colour(x, y);
      for (int k = 0; k < 3; ++k) img.row(y)[3 * x + k] = srgb_decode(float(c[k]) / 255.0f);
    }
  write_image(path, img);
}

// Which of red, green, blue a pixel shows: the channel more than 3x both others; 3 for a
// grey or white pixel (all channels within 20% of each other); -1 otherwise.
int dominant(const float* p) {
  for (int c = 0; c < 3; ++c)
    if (p[c] > 3.0f * p[(c + 1) % 3] && p[c] > 3.0f * p[(c + 2) % 3] && p[c] > 0.02f) return c;
  const float lo = std::min({p[0], p[1], p[2]}), hi = std::max({p[0], p[1], p[2]});
  return hi > 0.02f && lo > 0.8f * hi ? 3 : -1;
}

std::string rgb(const float* p) {
  return "(" + std::to_string(p[0]) + ", " + std::to_string(p[1]) + ", " + std::to_string(p[2]) + ")";
}

// A camera at z = 3 looking at a 2 x 2 quad at z = 0 that fills the whole view, a light at
// the camera and no ambient light. The quad's (u, v) run with x and y, so image row 0 (v = 1)
// is at the top.
const std::string kQuadView =
    "[camera]\nposition = [0, 0, 3]\nlook_at = [0, 0, 0]\nfov = 30\n"
    "[world]\nambient = [0, 0, 0]\n[[lights]]\nposition = [0, 0, 3]\n";
const std::string kQuadObj =
    "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "vn 0 0 1\nf 1/1/1 2/2/1 3/3/1 4/4/1\n";

// 2 x 2 texels: red, green (top row); blue, white (bottom row).
void write_quadrants(const std::string& path) {
  write_texels(path, 2, 2, [](int x, int y) -> std::array<int, 3> {
    if (y == 0) return x == 0 ? std::array{255, 0, 0} : std::array{0, 255, 0};
    return x == 0 ? std::array{0, 0, 255} : std::array{255, 255, 255};
  });
}

// The centre of each quadrant of the image shows that quadrant's texel.
void expect_quadrants(const Image& img) {
  const int a = kSize / 4, b = 3 * kSize / 4;
  EXPECT_EQ(dominant(pixel(img, a, a)), 0) << "top left " << rgb(pixel(img, a, a));
  EXPECT_EQ(dominant(pixel(img, b, a)), 1) << "top right " << rgb(pixel(img, b, a));
  EXPECT_EQ(dominant(pixel(img, a, b)), 2) << "bottom left " << rgb(pixel(img, a, b));
  EXPECT_EQ(dominant(pixel(img, b, b)), 3) << "bottom right " << rgb(pixel(img, b, b));
}

TEST(TexturedRender, MtlMapKdShowsEachTexelInItsQuadrantOnPhong) {
  const TempDir dir("textured_render");
  write_quadrants(dir.path("quad.png"));
  dir.write("quad.mtl", "newmtl tex\nKa 0 0 0\nKd 1 1 1\nmap_Kd quad.png\n");
  dir.write("quad.obj", "mtllib quad.mtl\nusemtl tex\n" + kQuadObj);
  const std::string scene = dir.write("scene.toml", kQuadView + "[[meshes]]\nfile = \"quad.obj\"\n");
  ASSERT_EQ(load_scene(scene).materials.at(0).model, Shading::phong);
  expect_quadrants(render_file(scene));
}

// A physically based quad: `extra` adds keys to its material.
std::string pbr_quad_scene(const TempDir& dir, const std::string& extra) {
  dir.write("quad.obj", kQuadObj);
  return dir.write("scene.toml", kQuadView +
                                     "[materials.tex]\nmodel = \"pbr\"\nroughness = 1\n" + extra +
                                     "[[meshes]]\nfile = \"quad.obj\"\nmaterial = \"tex\"\n");
}

TEST(TexturedRender, BaseColorTextureShowsEachTexelInItsQuadrantOnPbr) {
  const TempDir dir("textured_render");
  write_quadrants(dir.path("quad.png"));
  expect_quadrants(render_file(pbr_quad_scene(dir, "base_color_texture = \"quad.png\"\n")));
}

// A normal map of (0.5, 0.5, 1) everywhere (128, 128, 255: the nearest 8-bit values) is the
// unmapped normal; a tilted one turns the surface away from the light.
TEST(TexturedRender, AFlatNormalMapChangesNothingAndATiltedOneChangesTheImage) {
  const TempDir dir("textured_render");
  write_texels(dir.path("flat.png"), 4, 4, [](int, int) { return std::array{128, 128, 255}; });
  write_texels(dir.path("tilted.png"), 4, 4, [](int, int) { return std::array{230, 128, 200}; });
  const Image plain = render_file(pbr_quad_scene(dir, ""));
  const Image flat = render_file(pbr_quad_scene(dir, "normal_texture = \"flat.png\"\n"));
  const Image tilted = render_file(pbr_quad_scene(dir, "normal_texture = \"tilted.png\"\n"));
  double tilted_change = 0.0;
  for (std::size_t i = 0; i < plain.rgb.size(); ++i) {
    ASSERT_GT(plain.rgb[i], 0.0f) << i;  // the quad fills the view and is lit
    EXPECT_NEAR(flat.rgb[i], plain.rgb[i], 0.005f * plain.rgb[i] + 1e-6f) << i;
    tilted_change += std::fabs(tilted.rgb[i] - plain.rgb[i]) / plain.rgb[i];
  }
  EXPECT_GT(tilted_change / double(plain.rgb.size()), 0.05) << "mean relative change";
}

// A sphere's u runs around it: seen from +z, its left half has u < 1/2, its right half
// u > 1/2. A texture red on the left half and green on the right shows both, in that order.
TEST(TexturedRender, ASphereShowsBothHalvesOfItsTextureLeftAndRight) {
  const TempDir dir("textured_render");
  write_texels(dir.path("halves.png"), 8, 2, [](int x, int) {
    return x < 4 ? std::array{255, 0, 0} : std::array{0, 255, 0};
  });
  const std::string scene = dir.write(
      "scene.toml",
      "[camera]\nposition = [0, 0, 4]\nlook_at = [0, 0, 0]\nfov = 40\n"
      "[world]\nambient = [0, 0, 0]\n[[lights]]\nposition = [0, 0, 4]\n"
      "[materials.tex]\nambient = [0, 0, 0]\ndiffuse = [1, 1, 1]\ndiffuse_texture = \"halves.png\"\n"
      "[[spheres]]\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"tex\"\n");
  const Image img = render_file(scene);
  const int y = kSize / 2;
  for (const int x : {kSize / 4 + 1, 3 * kSize / 8}) {
    EXPECT_EQ(dominant(pixel(img, x, y)), 0) << "left " << x << " " << rgb(pixel(img, x, y));
    const int mirrored = kSize - 1 - x;
    EXPECT_EQ(dominant(pixel(img, mirrored, y)), 1)
        << "right " << mirrored << " " << rgb(pixel(img, mirrored, y));
  }
}

// Rays that meet nothing take the environment: a constant image gives its colour (times the
// intensity) everywhere.
TEST(TexturedRender, AConstantEnvironmentImageIsTheBackgroundOfEveryPixel) {
  const TempDir dir("textured_render");
  Image env(8, 4);
  for (std::size_t i = 0; i < env.rgb.size(); i += 3) {
    env.rgb[i] = 0.25f;
    env.rgb[i + 1] = 0.5f;
    env.rgb[i + 2] = 1.0f;
  }
  write_image(dir.path("env.exr"), env);
  for (const float intensity : {1.0f, 2.0f}) {
    const std::string scene = dir.write(
        "scene.toml", "[camera]\nposition = [0, 0, 0]\nlook_at = [0.3, 0.2, -1]\nfov = 90\n"
                      "[environment]\nimage = \"env.exr\"\nrotation = 30\nintensity = " +
                          std::to_string(intensity) + "\n");
    const Image img = render_file(scene);
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        const float* p = pixel(img, x, y);
        EXPECT_NEAR(p[0], 0.25f * intensity, 1e-4f) << x << "," << y;
        EXPECT_NEAR(p[1], 0.5f * intensity, 1e-4f) << x << "," << y;
        EXPECT_NEAR(p[2], 1.0f * intensity, 1e-4f) << x << "," << y;
      }
  }
}

}  // namespace
}  // namespace rt2

namespace rt2 {
namespace {

// A plane's texture lives in world coordinates, as the checker does: recentring the scene
// on a camera far from the origin (what rt2cpr does before rendering) moves no texel.
TEST(TexturedRender, RecentringOnTheCameraDoesNotMoveAPlanesTexture) {
  TempDir dir("textured_render");
  write_texels(dir.path("stripes.png"), 4, 4,
               [](int x, int) { return x % 2 ? std::array{255, 0, 0} : std::array{0, 0, 255}; });
  const std::string scene = dir.write("s.toml", R"(
[camera]
position = [3.3, 2, 1.7]
look_at = [3.3, 0, 1.7]
up = [0, 0, -1]
fov = 40
[materials.m]
ambient = [0, 0, 0]
diffuse = [1, 1, 1]
diffuse_texture = "stripes.png"
[[lights]]
position = [3.3, 5, 1.7]
[[planes]]
normal = [0, 1, 0]
offset = 0
material = "m"
)");
  Scene s = load_scene(scene);
  const Image here = test::render_scene(s, settings());
  recenter_on_camera(s);
  const Image recentred = test::render_scene(s, settings());
  int red = 0, blue = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      EXPECT_EQ(dominant(pixel(here, x, y)), dominant(pixel(recentred, x, y)))
          << x << "," << y << ": " << rgb(pixel(here, x, y)) << " vs "
          << rgb(pixel(recentred, x, y));
      red += dominant(pixel(here, x, y)) == 0;
      blue += dominant(pixel(here, x, y)) == 2;
    }
  EXPECT_GT(red, 50);
  EXPECT_GT(blue, 50);
}

}  // namespace
}  // namespace rt2
