// The viewer's settings by name (rt2cpr/viewer/controls.h), as a script's `set` and the
// panel change them: each takes effect, and a bad value changes nothing.
#include "rt2cpr/viewer/controls.h"

#include <gtest/gtest.h>

#include "tests/rt2/error_of.h"

namespace rt2cpr::viewer {
namespace {

TEST(Controls, EverySettingTakesEffect) {
  Controls c;
  set_control(c, "depth", "9");
  set_control(c, "min-weight", "0.25");
  set_control(c, "subpixels", "5");
  set_control(c, "pattern", "circle");
  set_control(c, "lights", "12");
  set_control(c, "triangle-test", "watertight");
  set_control(c, "threads", "3");
  set_control(c, "backend", "tbb");
  set_control(c, "overlay", "off");
  EXPECT_EQ(c.settings.depth, 9);
  EXPECT_EQ(c.settings.min_weight, 0.25f);
  EXPECT_EQ(c.settings.subpixels, 5);
  EXPECT_EQ(c.settings.pattern, rt2::Pattern::circle);
  EXPECT_EQ(c.lights, 12);
  EXPECT_TRUE(c.settings.watertight);
  EXPECT_EQ(c.schedule.threads, 3);
  EXPECT_EQ(c.schedule.backend, rt2::Backend::tbb);
  EXPECT_FALSE(c.overlay);
}

TEST(Controls, ABadValueOrNameIsOneLineAndChangesNothing) {
  Controls c;
  c.settings.depth = 4;
  const struct {
    const char *name, *value, *says;
  } cases[] = {
      {"depth", "-1", "depth must be an integer in [0, 1000000]"},
      {"depth", "4.5", "depth must be an integer"},
      {"depth", "", "depth must be an integer"},
      {"min-weight", "nan", "min-weight must be a number in [0, 1]"},
      {"min-weight", "2", "min-weight must be a number in [0, 1]"},
      {"subpixels", "0", "subpixels must be an integer in [1, 65536]"},
      {"pattern", "hex", "pattern"},
      {"lights", "99999999999", "lights must be an integer"},
      {"triangle-test", "slow", "unknown triangle test 'slow'"},
      {"threads", "0", "threads must be an integer in [1, 1024]"},
      {"backend", "mpi", "unknown backend 'mpi'"},
      {"overlay", "maybe", "overlay must be on or off"},
      {"fov", "30", "unknown setting 'fov' (expected depth, min-weight"},
  };
  for (const auto& k : cases) {
    const Controls before = c;
    const std::string e = rt2::test::error_of([&] { set_control(c, k.name, k.value); });
    EXPECT_NE(e.find(k.says), std::string::npos) << k.name << " " << k.value << " -> " << e;
    EXPECT_EQ(c.settings.depth, before.settings.depth);
    EXPECT_EQ(c.settings.min_weight, before.settings.min_weight);
    EXPECT_EQ(c.lights, before.lights);
    EXPECT_EQ(c.schedule.threads, before.schedule.threads);
  }
}

}  // namespace
}  // namespace rt2cpr::viewer
