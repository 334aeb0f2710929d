// mlib/timer.cpp — TSC calibration, the rdtscp check and the steady_clock fallback.
#include "mlib/timer.h"

#include <cpuid.h>

#include <cstdio>
#include <mutex>
#include <stdexcept>

namespace mlib {

namespace {

double cached_frequency() {
  static const double hz = Timer::Calibrate();
  return hz;
}

void warn_fallback_once() {
  static std::once_flag once;
  std::call_once(once, [] {
    std::fprintf(stderr,
                 "mlib::Timer: this CPU has no rdtscp; timing with std::chrono::steady_clock "
                 "(ticks are nanoseconds)\n");
  });
}

}  // namespace

bool Timer::HasRdtscp() {
  unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
  if (__get_cpuid_max(0x80000000u, nullptr) < 0x80000001u) return false;
  __cpuid(0x80000001u, eax, ebx, ecx, edx);
  return (edx >> 27) & 1u;
}

double Timer::Calibrate(std::chrono::nanoseconds interval) {
  if (!HasRdtscp()) return 1e9;  // the fallback's ticks are nanoseconds
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  const std::uint64_t c0 = tsc_start();
  auto t1 = clock::now();
  while (t1 - t0 < interval) t1 = clock::now();
  const std::uint64_t c1 = tsc_stop();
  const auto t2 = clock::now();
  // The counter read sits between t1 and t2; take the midpoint of the wall-clock bracket.
  const double ns = std::chrono::duration<double, std::nano>(t1 - t0).count() +
                    0.5 * std::chrono::duration<double, std::nano>(t2 - t1).count();
  return static_cast<double>(c1 - c0) * 1e9 / ns;
}

Timer::Timer(Mode mode, Clock clock) : mode_(mode) {
  steady_ = clock == Clock::steady || !HasRdtscp();
  if (clock == Clock::tsc && steady_) warn_fallback_once();
  frequency_ = steady_ ? 1e9 : cached_frequency();
}

Timer::Timer(Mode mode, double ticks_per_second) : mode_(mode), frequency_(ticks_per_second) {
  if (!(ticks_per_second > 0.0)) throw std::invalid_argument("Timer: frequency must be > 0");
  steady_ = !HasRdtscp();
  if (steady_) {
    warn_fallback_once();
    frequency_ = 1e9;
  }
}

void Timer::Reset() {
  start_ = last_ = sum_ = max_ = laps_ = 0;
  min_ = std::numeric_limits<std::uint64_t>::max();
}

std::uint64_t Timer::Ticks(Mode mode) const {
  if (laps_ == 0) return 0;
  switch (mode) {
    case Mode::sum: return sum_;
    case Mode::min: return min_;
    case Mode::max: return max_;
    case Mode::avg: return sum_ / laps_;
  }
  return 0;
}

}  // namespace mlib
