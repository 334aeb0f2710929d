// The moving frames' resolution (rt2cpr/viewer/resolution_scaler.h): coarser while frames
// come slower than the target, finer again when the finer one keeps the target with a 25 %
// margin, never past its bounds, never on too few frames, never with no target.
#include "rt2cpr/viewer/resolution_scaler.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rt2cpr::viewer {
namespace {

// Frames whose cost scales with their pixels: `full` seconds at scale 1.
void frames(ResolutionScaler& s, double full, int n) {
  for (int i = 0; i < n; ++i) s.add(full / (double(s.scale()) * s.scale()));
}

TEST(ResolutionScaler, LowersTheResolutionUntilTheTargetIsMetAndNoFurther) {
  ResolutionScaler s(30.0);
  frames(s, 1.0 / 20.0, 100);  // 20 fps at full size: 1/2 gives 80 fps
  EXPECT_EQ(s.scale(), 2);
  ResolutionScaler t(30.0);
  frames(t, 1.0 / 40.0, 100);  // fast enough: stays
  EXPECT_EQ(t.scale(), 1);
  ResolutionScaler slow(30.0);
  frames(slow, 10.0, 200);  // 0.1 fps: bottoms out at 1/8
  EXPECT_EQ(slow.scale(), ResolutionScaler::kMaxScale);
}

TEST(ResolutionScaler, RaisesItAgainWhenTheFinerOneKeepsTheTargetWithAMargin) {
  ResolutionScaler s(30.0);
  frames(s, 1.0 / 10.0, 200);  // 10 fps at full size: 1/2 gives 40 fps
  EXPECT_EQ(s.scale(), 2);
  frames(s, 1.0 / 40.0, 200);  // the scene got cheaper: 40 fps at full size
  EXPECT_EQ(s.scale(), 1);
  ResolutionScaler m(30.0);
  frames(m, 1.0 / 20.0, 100);
  frames(m, 1.0 / 33.0, 200);  // 33 fps at full size is under 1.25 x 30: stays at 1/2
  EXPECT_EQ(m.scale(), 2);
}

TEST(ResolutionScaler, NeedsSixFramesAndATargetAndIgnoresBadIntervals) {
  ResolutionScaler s(30.0);
  frames(s, 1.0, 5);
  EXPECT_EQ(s.scale(), 1);
  s.restart();
  frames(s, 1.0, 5);
  EXPECT_EQ(s.scale(), 1);
  s.add(1.0);
  EXPECT_EQ(s.scale(), 2);
  ResolutionScaler none(0.0);
  frames(none, 10.0, 100);
  EXPECT_EQ(none.scale(), 1);
  ResolutionScaler bad(30.0);
  for (double v : {0.0, -1.0, std::nan(""), 0.0, -5.0, std::nan("")}) bad.add(v);
  EXPECT_EQ(bad.scale(), 1);
}

}  // namespace
}  // namespace rt2cpr::viewer
