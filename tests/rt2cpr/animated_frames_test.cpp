// rt2cpr with an animated glTF (tests/rt2/io/animated_gltf.h): every frame of a sequence
// (its trees refit) equals, bit for bit, a fresh render at that frame's time, whatever the
// thread count; `--output` with '#' writes every frame under its number; the options of
// animation are checked. Each test names the property it checks.
#include <gtest/gtest.h>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "rt2/image/image_io.h"
#include "tests/rt2/io/animated_gltf.h"
#include "tests/rt2cpr/cli_fixture.h"

namespace {

using rt2::test::Cli;
using rt2::test::Outcome;

constexpr const char* kSmall = "--width 48 --height 32 --quiet";

std::string exact(double x) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", x);
  return text;
}

class AnimatedFrames : public Cli {
 protected:
  void SetUp() override { write("a.gltf", rt2::test::animated_gltf()); }
  std::string scene() const { return path("a.gltf"); }
  void expect_same_pixels(const std::string& a, const std::string& b) const {
    const rt2::Image x = rt2::read_image(a), y = rt2::read_image(b);
    ASSERT_EQ(x.rgb.size(), y.rgb.size());
    EXPECT_TRUE(x.rgb == y.rgb) << a << " differs from " << b;
  }
};

TEST_F(AnimatedFrames, EveryFrameOfRefitTreesEqualsAFreshRenderAtItsTimeAtAnyThreadCount) {
  const Outcome seq = run(scene() + " " + kSmall + " --frames 4 --fps 3 --time 0.2 --threads 2 " +
                          "--stats " + path("s.json") + " --output " + path("seq_##.exr"));
  ASSERT_EQ(seq.status, 0) << seq.err;
  // The meshes keep their triangles from pose to pose: every later frame refits the trees
  // (and rebuilds them only if they degraded), none builds them afresh.
  const nlohmann::json j = nlohmann::json::parse(slurp(path("s.json")));
  EXPECT_EQ(j["pose_trees"]["refit"].get<int>() + j["pose_trees"]["rebuilt"].get<int>(), 3) << j;
  EXPECT_EQ(j["pose_trees"]["built"].get<int>(), 0) << j;
  for (int f = 0; f < 4; ++f) {
    const std::string one = path("one_" + std::to_string(f) + ".exr");
    const Outcome r = run(scene() + " " + kSmall + " --threads 1 --time " + exact(0.2 + f / 3.0) +
                          " --output " + one);
    ASSERT_EQ(r.status, 0) << r.err;
    expect_same_pixels(path("seq_0" + std::to_string(f + 1) + ".exr"), one);
  }
  // The frames differ from each other: the scene moved.
  const rt2::Image first = rt2::read_image(path("seq_01.exr")),
                   last = rt2::read_image(path("seq_04.exr"));
  EXPECT_FALSE(first.rgb == last.rgb);
}

TEST_F(AnimatedFrames, WithoutHashesOnlyTheLastFrameIsWrittenAndItIsTheLastTime) {
  ASSERT_EQ(run(scene() + " " + kSmall + " --frames 3 --output " + path("last.exr")).status, 0);
  ASSERT_EQ(run(scene() + " " + kSmall + " --time " + exact(2 / 30.0) + " --output " +
                path("fresh.exr"))
                .status,
            0);
  expect_same_pixels(path("last.exr"), path("fresh.exr"));
}

TEST_F(AnimatedFrames, HashesNameEveryFrameZeroPaddedAndTheRunIsReported) {
  const Outcome r = run(scene() + " --width 16 --height 12 --frames 3 --animation hop " +
                        "--stats " + path("s.json") + " --output " + path("f_####.png"));
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* name : {"f_0001.png", "f_0002.png", "f_0003.png"})
    EXPECT_TRUE(std::filesystem::exists(path(name))) << name;
  EXPECT_FALSE(std::filesystem::exists(path("f_####.png")));
  EXPECT_NE(r.out.find("wrote 3 frames, " + path("f_0001.png") + " ... " + path("f_0003.png")),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("animation 1 'hop' of 2, 1.000 s long"), std::string::npos) << r.out;
  const nlohmann::json j = nlohmann::json::parse(slurp(path("s.json")));
  EXPECT_EQ(j["animation"]["name"], "hop");
  EXPECT_TRUE(j.contains("pose_ms"));
}

TEST_F(AnimatedFrames, NumbersLongerThanTheHashesAreWrittenWholeAndFoldersKeepTheirHashes) {
  std::filesystem::create_directory(path("d#"));
  ASSERT_EQ(run(scene() + " --width 8 --height 6 --quiet --frames 11 --output " +
                path("d#/g_#.png"))
                .status,
            0);
  for (const char* name : {"d#/g_1.png", "d#/g_9.png", "d#/g_10.png", "d#/g_11.png"})
    EXPECT_TRUE(std::filesystem::exists(path(name))) << name;
  ASSERT_EQ(run(scene() + " --width 8 --height 6 --quiet --frames 2 --output " +
                path("d#/still.png"))
                .status,
            0);
  EXPECT_TRUE(std::filesystem::exists(path("d#/still.png")));
}

TEST_F(AnimatedFrames, AnimationOptionsAreCheckedWithOneLine) {
  expect_clean_failure(run(scene() + " " + kSmall + " --fps 0"), "fps must be in [0.001, 1000000]");
  expect_clean_failure(run(scene() + " " + kSmall + " --time nan"), "time");
  expect_clean_failure(run(scene() + " " + kSmall + " --animation walk"),
                       "has no animation 'walk' (its 2: #0 'spin', #1 'hop')");
  expect_clean_failure(run(std::string(kSmall) + " --animation spin"),
                       "the built-in scene has no animations");
}

}  // namespace
