// The viewer's camera (rt2cpr/viewer/fly_camera.h): it starts as the scene's camera, its
// printed [camera] table reads back as the very camera it renders through, and it moves
// and turns as a first-person camera should, also at the extremes (looking straight down,
// far from the origin, huge turns).
#include "rt2cpr/viewer/fly_camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "rt2/scene/builtin_scene.h"
#include "rt2/io/scene_io.h"
#include "tests/rt2/temp_dir.h"

namespace rt2cpr::viewer {
namespace {

using rt2::vec4;

bool same_bits(const vec4& a, const vec4& b) {
  const float x[3] = {a.x(), a.y(), a.z()}, y[3] = {b.x(), b.y(), b.z()};
  return std::memcmp(x, y, sizeof x) == 0;
}

bool same_camera(const rt2::Camera& a, const rt2::Camera& b) {
  return same_bits(a.position(), b.position()) && same_bits(a.forward(), b.forward()) &&
         same_bits(a.up(), b.up()) && same_bits(a.right(), b.right()) && a.fov() == b.fov();
}

TEST(FlyCamera, StartsAsTheScenesCameraBitForBit) {
  const rt2::Camera builtin = rt2::make_default_scene().camera;
  EXPECT_TRUE(same_camera(FlyCamera(builtin, 1.0f).camera(), builtin));
  const rt2::Camera glass = rt2::load_scene(std::string(RT2_SOURCE_DIR) + "/scenes/glass.toml").camera;
  EXPECT_TRUE(same_camera(FlyCamera(glass, 1.0f).camera(), glass));
}

// A rolled camera (its up not an axis) keeps its roll until the first turn: its view is the
// scene's up to rounding, and its printed table still reads back bit for bit.
TEST(FlyCamera, ARolledCameraKeepsItsRollUntilTheFirstTurn) {
  rt2::test::TempDir dir("fly");
  const rt2::Camera rolled(vec4(1, 2, 3), vec4(0.2f, -0.1f, -1), vec4(0.3f, 1, 0), 50.0f);
  FlyCamera fly(rolled, 1.0f);
  const rt2::Camera c = fly.camera();
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(c.up()[i], rolled.up()[i], 1e-6f);
    EXPECT_NEAR(c.right()[i], rolled.right()[i], 1e-6f);
    EXPECT_EQ(c.forward()[i], rolled.forward()[i]);
  }
  EXPECT_TRUE(same_camera(rt2::load_camera(dir.write("cam.toml", fly.toml())), c));
  fly.turn(1.0f, 0.0f);
  EXPECT_NEAR(fly.camera().right().y(), 0.0f, 1e-6f);  // level: first person, no roll
}

// The property the viewer's `C` key rests on: whatever the moves and turns, the printed
// table, read as a scene file's camera is read, is the camera the viewer renders through.
TEST(FlyCamera, PrintedTableReadsBackAsTheSameCameraBitForBit) {
  rt2::test::TempDir dir("fly");
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  FlyCamera fly(rt2::make_default_scene().camera, 3.0f);
  for (int i = 0; i < 200; ++i) {
    fly.turn(400.0f * u(rng), 200.0f * u(rng));
    fly.move(u(rng), u(rng), u(rng), 0.5f + u(rng));
    if (i == 100) fly.scale_speed(60.0f);  // far from the origin: large coordinates
    const std::string path = dir.write("cam.toml", fly.toml());
    ASSERT_TRUE(same_camera(rt2::load_camera(path), fly.camera())) << fly.toml();
  }
}

TEST(FlyCamera, PitchStopsShortOfStraightUpOrDown) {
  FlyCamera fly(rt2::Camera(vec4(0, 0, 0), vec4(0, 0, -1), vec4(0, 1, 0), 60.0f), 1.0f);
  fly.turn(0.0f, -1e6f);  // the mouse far up
  const float up = fly.camera().forward().y();
  EXPECT_NEAR(up, std::sin(89.0 * M_PI / 180.0), 1e-5);
  fly.turn(1e6f, 2e6f);  // far down, and around many times
  EXPECT_NEAR(fly.camera().forward().y(), -std::sin(89.0 * M_PI / 180.0), 1e-5);
  for (float v : {fly.camera().forward().x(), fly.camera().forward().z()}) EXPECT_TRUE(std::isfinite(v));
}

TEST(FlyCamera, MovesAlongTheViewTheRightAndTheUpAxisAtItsSpeed) {
  const rt2::Camera start(vec4(1, 2, 3), vec4(0, 0, -1), vec4(0, 1, 0), 60.0f);
  FlyCamera fly(start, 2.0f);
  fly.move(1.0f, 0.0f, 0.0f, 1.5f);
  EXPECT_TRUE(same_bits(fly.camera().position(), vec4(1, 2, 0)));
  fly.move(0.0f, 1.0f, 0.0f, 0.5f);  // right of looking along -z is +x
  EXPECT_TRUE(same_bits(fly.camera().position(), vec4(2, 2, 0)));
  fly.move(0.0f, 0.0f, -1.0f, 1.0f);
  EXPECT_TRUE(same_bits(fly.camera().position(), vec4(2, 0, 0)));
  fly.turn(450.0f, 0.0f);  // 90 degrees to the right: now looking along +x
  const vec4 f = fly.camera().forward();
  EXPECT_NEAR(f.x(), 1.0f, 1e-6f);
  EXPECT_NEAR(f.z(), 0.0f, 1e-6f);
}

// A scene camera looking straight down (its up along -z): the heading comes from its up
// vector, and sideways movement stays finite.
TEST(FlyCamera, LookingStraightDownStillMovesSideways) {
  const rt2::Camera down(vec4(0, 10, 0), vec4(0, -1, 0), vec4(0, 0, -1), 60.0f);
  FlyCamera fly(down, 1.0f);
  EXPECT_TRUE(same_camera(fly.camera(), down));
  fly.move(0.0f, 1.0f, 0.0f, 1.0f);
  const vec4 p = fly.camera().position();
  for (float v : {p.x(), p.y(), p.z()}) EXPECT_TRUE(std::isfinite(v));
  EXPECT_NEAR(std::hypot(p.x(), p.z()), 1.0f, 1e-6f);
  EXPECT_EQ(p.y(), 10.0f);
}

// Flown as far as the speed allows, the camera stops where a scene file can still put it,
// and its printed table reads back.
TEST(FlyCamera, FarFlightsStopWhereASceneFileCanStillPutTheCamera) {
  rt2::test::TempDir dir("fly");
  FlyCamera fly(rt2::make_default_scene().camera, 1.0f);
  fly.scale_speed(1e6f);
  for (int i = 0; i < 100; ++i) fly.move(1.0f, 0.5f, -0.3f, 1e6f);
  const vec4 p = fly.camera().position();
  for (float v : {p.x(), p.y(), p.z()}) EXPECT_LE(std::fabs(v), 1e15f);
  EXPECT_TRUE(same_camera(rt2::load_camera(dir.write("cam.toml", fly.toml())), fly.camera()));
}

TEST(FlyCamera, SpeedStaysWithinItsBounds) {
  FlyCamera fly(rt2::make_default_scene().camera, 1.0f);
  fly.scale_speed(1e6f);
  EXPECT_EQ(fly.speed(), 1e9f);
  fly.scale_speed(-1e6f);
  EXPECT_EQ(fly.speed(), 1e-6f);
  fly.scale_speed(std::nanf(""));  // never NaN
  EXPECT_TRUE(std::isfinite(fly.speed()));
}

}  // namespace
}  // namespace rt2cpr::viewer
