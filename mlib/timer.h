// mlib/timer.h — a cycle-accurate interval timer (thesis 5.2); method names follow the
// thesis's Timer (Start, Stop, Reset, ...).
//
// Start() serialises with `cpuid` and then reads the time-stamp counter (`rdtsc`); Stop()
// reads it with `rdtscp`, which waits for all earlier instructions, and then runs `cpuid`
// so that later instructions cannot move into the measured interval. Each Start/Stop pair
// is one lap; the timer keeps the sum, minimum, maximum and count of laps and reports one
// of them according to its Mode (avg = sum / count). Without `rdtscp` (CPUID
// 0x80000001:EDX bit 27) it falls back to steady_clock, counts nanoseconds as ticks
// (frequency 1e9), and says so once on stderr; Clock::steady asks for that fallback.
#pragma once

#include <chrono>
#include <cstdint>
#include <limits>

namespace mlib {

class Timer {
 public:
  enum class Mode { sum, min, max, avg };
  enum class Clock { tsc, steady };

  // Calibrates the TSC frequency: the counter against std::chrono::steady_clock over 50 ms,
  // once per process (later Timers reuse the figure), so only the first construction waits.
  // Clock::tsc falls back to steady when rdtscp is missing.
  explicit Timer(Mode mode = Mode::sum, Clock clock = Clock::tsc);
  // Uses the given TSC frequency in Hz (must be > 0); no calibration.
  Timer(Mode mode, double ticks_per_second);

  void Start() {
    start_ = steady_ ? steady_now() : tsc_start();
  }
  void Stop() {
    const std::uint64_t end = steady_ ? steady_now() : tsc_stop();
    Record(end - start_);
  }
  // Adds one interval of `ticks` measured elsewhere (Stop() calls this).
  void Record(std::uint64_t ticks) {
    last_ = ticks;
    sum_ += ticks;
    min_ = ticks < min_ ? ticks : min_;
    max_ = ticks > max_ ? ticks : max_;
    ++laps_;
  }
  // Forgets every lap; keeps the mode, the clock and the frequency.
  void Reset();

  // The timer's mode over all laps so far, in ticks (0 when there was no lap).
  std::uint64_t Ticks() const { return Ticks(mode_); }
  std::uint64_t Ticks(Mode mode) const;
  double Seconds() const { return Seconds(mode_); }
  double Seconds(Mode mode) const { return static_cast<double>(Ticks(mode)) / frequency_; }
  std::uint64_t Last() const { return last_; }
  std::uint64_t Laps() const { return laps_; }
  Mode GetMode() const { return mode_; }
  void SetMode(Mode mode) { mode_ = mode; }
  double Frequency() const { return frequency_; }
  bool UsesSteadyClock() const { return steady_; }

  // Whether this CPU has rdtscp (CPUID 0x80000001:EDX bit 27).
  static bool HasRdtscp();
  // Measures the TSC frequency against steady_clock over `interval` (Hz). Not cached.
  static double Calibrate(std::chrono::nanoseconds interval = std::chrono::milliseconds(50));

 private:
  static std::uint64_t steady_now() {
    return static_cast<std::uint64_t>(
        std::chrono::duration_cast<std::chrono::nanoseconds>(
            std::chrono::steady_clock::now().time_since_epoch())
            .count());
  }
  // cpuid (serialise), then rdtsc.
  static std::uint64_t tsc_start() {
    std::uint32_t lo, hi;
    asm volatile("cpuid\n\trdtsc" : "=a"(lo), "=d"(hi) : "a"(0) : "rbx", "rcx", "memory");
    return (static_cast<std::uint64_t>(hi) << 32) | lo;
  }
  // rdtscp (after all earlier work), keep the result, then cpuid (fence later work).
  static std::uint64_t tsc_stop() {
    std::uint32_t lo, hi;
    asm volatile("rdtscp\n\tmov %%eax, %0\n\tmov %%edx, %1\n\txor %%eax, %%eax\n\tcpuid"
                 : "=r"(lo), "=r"(hi)
                 :
                 : "rax", "rbx", "rcx", "rdx", "memory");
    return (static_cast<std::uint64_t>(hi) << 32) | lo;
  }

  Mode mode_;
  bool steady_;
  double frequency_;
  std::uint64_t start_ = 0;
  std::uint64_t last_ = 0;
  std::uint64_t sum_ = 0;
  std::uint64_t min_ = std::numeric_limits<std::uint64_t>::max();
  std::uint64_t max_ = 0;
  std::uint64_t laps_ = 0;
};

}  // namespace mlib
