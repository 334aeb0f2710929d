// rt2cpr's scene set-up (rt2cpr/scene_setup.h) end to end: a framed camera fitted to the
// image, --camera never refitted, --environment sky keeping the scene's sky, and the warning
// for --lights that white the image out.
#include <gtest/gtest.h>

#include <string>

#include "rt2/image/image_io.h"
#include "tests/rt2cpr/cli_fixture.h"

namespace {

using rt2::test::Cli;
using rt2::test::Outcome;

// A red box four times as wide as it is high and deep: all that is red in its render.
const char* kWideBox =
    "mtllib box.mtl\nusemtl red\n"
    "v -2 0 -0.5\nv 2 0 -0.5\nv 2 1 -0.5\nv -2 1 -0.5\n"
    "v -2 0 0.5\nv 2 0 0.5\nv 2 1 0.5\nv -2 1 0.5\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n";
const char* kRed = "newmtl red\nKa 1 0 0\nKd 1 0 0\n";

bool red(const float* p) { return p[0] > p[1] + 0.05f && p[0] > p[2] + 0.05f; }

// The red pixels of `image`: how many, and how many on its border.
std::pair<int, int> red_pixels(const rt2::Image& image) {
  int all = 0, border = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      if (!red(image.pixel(x, y))) continue;
      ++all;
      border += x == 0 || y == 0 || x == image.width - 1 || y == image.height - 1;
    }
  return {all, border};
}

TEST_F(Cli, ABareObjIsFittedToTheImageAtEveryAspect) {
  write("box.obj", kWideBox);
  write("box.mtl", kRed);
  // Portrait and wide; rt2/io/framing_test.cpp checks the camera at 4:3 and 16:9 too.
  for (const auto& [w, h] : {std::pair{24, 72}, std::pair{96, 32}}) {
    const std::string out = path("box" + std::to_string(w) + "x" + std::to_string(h) + ".exr");
    const Outcome r = run(path("box.obj") + " --quiet --width " + std::to_string(w) +
                          " --height " + std::to_string(h) + " --output " + out);
    ASSERT_EQ(r.status, 0) << r.err;
    const auto [all, border] = red_pixels(rt2::read_image(out));
    EXPECT_GT(all, w * h / 20) << w << " x " << h;  // the box is seen ...
    EXPECT_EQ(border, 0) << w << " x " << h;        // ... whole
  }
}

TEST_F(Cli, ACameraOptionIsNeverFitted) {
  write("box.obj", kWideBox);
  write("box.mtl", kRed);
  // Looking away from the box: fitted, the camera would see it.
  write("away.toml", "[camera]\nposition = [0, 0.5, 10]\ndirection = [0, 0, 1]\n");
  const Outcome r = run(path("box.obj") + " --quiet --width 24 --height 72 --camera " +
                        path("away.toml") + " --output " + path("away.exr"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(red_pixels(rt2::read_image(path("away.exr"))).first, 0);
}

// The scene's own sky and `--environment sky` on it: the same bits. Replacing the
// environment by a default sky moved the sun and lost the intensity and rotation.
TEST_F(Cli, EnvironmentSkyKeepsTheScenesSunIntensityAndRotation) {
  write("ball.toml",
        "[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\n"
        "[environment]\nsun_direction = [-0.6, 0.3, -0.7]\nintensity = 0.4\nrotation = 70\n"
        "[materials.m]\nmodel = \"pbr\"\nroughness = 0.5\n"
        "[[spheres]]\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"m\"\n");
  const std::string base = std::string(rt2::test::kTiny) + " --scene " + path("ball.toml");
  ASSERT_EQ(run(base + " --output " + path("own.exr")).status, 0);
  const Outcome r = run(base + " --environment sky --output " + path("sky.exr"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(rt2::read_image(path("own.exr")).rgb, rt2::read_image(path("sky.exr")).rgb);
}

// The built-in scene has one light and no light field: --lights adds ring lights of its
// intensity and no range.
TEST_F(Cli, LightsThatWhiteTheImageOutAreOneWarning) {
  const std::string base = "--width 8 --height 6 --quiet --output " + path("l.png");
  const Outcome many = run(base + " --lights 50");
  ASSERT_EQ(many.status, 0) << many.err;
  EXPECT_EQ(many.err.rfind("warning: --lights 50 adds 49 lights without a range, 50 times", 0), 0u)
      << many.err;
  EXPECT_NE(many.err.find("--light-range"), std::string::npos) << many.err;
  EXPECT_EQ(many.err.find('\n'), many.err.size() - 1) << "not one line: " << many.err;
  for (const char* fine : {" --lights 4", " --lights 50 --light-range 2"}) {
    const Outcome r = run(base + fine);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "") << fine;
  }
}

}  // namespace
