// rt2cpr/viewer/resolution_scaler.h — the resolution of the viewer's moving frames: one step
// coarser when they come slower than the target rate, one finer when the finer one would
// still keep it with a 25 % margin (a frame's cost scales with its pixels, 1 / scale^2).
//
// Each frame is measured by the time the renderer was busy with it: the interval from the
// previous frame shown to this one, less the time the worker waited for its request (a slow
// mouse drag is not a slow renderer). Decided on the median of the last intervals, at least
// six since the last change.
#pragma once

#include <vector>

namespace rt2cpr::viewer {

class ResolutionScaler {
 public:
  static constexpr int kMaxScale = 8;  // the divisor of width and height: 1 ... kMaxScale

  // target_fps <= 0: never lowers the resolution.
  explicit ResolutionScaler(double target_fps) : target_(target_fps) {}
  int scale() const { return scale_; }
  // Starts measuring afresh (the camera started moving: the last interval is not a frame's).
  void restart() { intervals_.clear(); }
  // A moving frame took `seconds` of the renderer's time since the previous one.
  void add(double seconds);

 private:
  double target_;
  int scale_ = 1;
  std::vector<double> intervals_;
};

}  // namespace rt2cpr::viewer
