// The viewer's frame log (rt2cpr/viewer/frame_log.h): the moving frame rate is the median
// interval between consecutive moving frames, and the CSV has one line per frame.
#include "rt2cpr/viewer/frame_log.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace rt2cpr::viewer {
namespace {

TEST(FrameLog, MovingRateIsTheMedianIntervalBetweenConsecutiveMovingFrames) {
  FrameLog log;
  EXPECT_EQ(log.moving_fps(), 0.0);
  // Moving frames 25 ms apart, one slow one (100 ms), a still in between whose gap is not
  // a moving interval.
  double t = 0.0;
  for (double dt : {0.0, 0.025, 0.025, 0.1, 0.025, 0.025}) log.add({t += dt, true, 0, 1, 64, 48, 20.0, 100});
  log.add({t + 1.0, false, 1, 4, 64, 48, 30.0, 100});
  log.add({t + 5.0, true, 0, 1, 32, 24, 5.0, 100});
  log.add({t + 5.02, true, 0, 1, 32, 24, 5.0, 100});
  // Intervals: 25, 25, 100, 25, 25, 20 ms: median 25 ms.
  EXPECT_NEAR(log.moving_fps(), 40.0, 1e-6);
  const std::string s = log.summary();
  EXPECT_NE(s.find("moving: 8 frames"), std::string::npos) << s;
  EXPECT_NE(s.find("64x48 (6)"), std::string::npos) << s;
  EXPECT_NE(s.find("32x24 (2)"), std::string::npos) << s;
}

TEST(FrameLog, CsvHasAHeaderAndOneLinePerFrame) {
  FrameLog log;
  log.add({0.5, false, 2, 4, 640, 480, 12.5, 1234});
  log.add({0.75, true, 0, 1, 320, 240, 3.25, 99});
  const std::string csv = log.csv();
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 3);
  EXPECT_EQ(csv.rfind("time_s,kind,pass,passes,width,height,render_ms,rays\n", 0), 0u);
  EXPECT_NE(csv.find("0.5000,still,2,4,640,480,12.500,1234\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find("0.7500,moving,0,1,320,240,3.250,99\n"), std::string::npos) << csv;
}

}  // namespace
}  // namespace rt2cpr::viewer
