// rt2cpr/viewer/resolution_scaler.cpp — the median rule.
#include "rt2cpr/viewer/resolution_scaler.h"

#include <algorithm>

namespace rt2cpr::viewer {

void ResolutionScaler::add(double seconds) {
  if (target_ <= 0.0 || !(seconds > 0.0)) return;
  intervals_.push_back(seconds);
  if (intervals_.size() > 30) intervals_.erase(intervals_.begin());
  if (intervals_.size() < 6) return;
  std::vector<double> v = intervals_;
  std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
  const double fps = 1.0 / v[v.size() / 2];
  if (fps < target_ && scale_ < kMaxScale) {
    ++scale_;
    intervals_.clear();
  } else if (scale_ > 1) {
    const double finer = double(scale_ - 1) / double(scale_);
    if (fps * finer * finer > 1.25 * target_) {
      --scale_;
      intervals_.clear();
    }
  }
}

}  // namespace rt2cpr::viewer
