// tests/bench/bench_util.h — what the micro-benchmarks share: the fixed cost of a timer lap
// (subtracted from every measured lap) and the median of a sample.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "mlib/timer.h"

namespace bench {

// The fixed cost of an empty Start/Stop lap (the minimum over many).
inline std::uint64_t empty_lap_ticks(double hz) {
  mlib::Timer t(mlib::Timer::Mode::min, hz);
  for (int i = 0; i < 20000; ++i) {
    t.Start();
    t.Stop();
  }
  return t.Ticks();
}

// The median of `v` (the mean of the middle two for an even count); 0 when empty.
inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace bench
