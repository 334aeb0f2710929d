// rt2cpr/clock.h — the wall clock rt2cpr times its steps with.
#pragma once

#include <chrono>

namespace rt2cpr {

using Clock = std::chrono::steady_clock;

// Milliseconds from `t0` to now.
inline double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

}  // namespace rt2cpr
