// mlib::Timer: the four modes on known sequences, Reset, the calibration against
// steady_clock, the explicit-frequency constructor and the steady_clock fallback.
#include "mlib/timer.h"

#include <gtest/gtest.h>

#include <chrono>
#include <stdexcept>
#include <thread>

namespace mlib {
namespace {

using namespace std::chrono_literals;

// A timer that never calibrates: laps are fed with Record().
Timer known_sequence(Timer::Mode mode) {
  Timer t(mode, 1e9);
  for (std::uint64_t ticks : {50u, 30u, 100u, 20u}) t.Record(ticks);
  return t;
}

void spin_for(std::chrono::nanoseconds d) {
  const auto end = std::chrono::steady_clock::now() + d;
  while (std::chrono::steady_clock::now() < end) {
  }
}

TEST(Timer, SumModeAddsAllLaps) {
  EXPECT_EQ(known_sequence(Timer::Mode::sum).Ticks(), 200u);
}

TEST(Timer, MinModeKeepsTheShortestLap) {
  EXPECT_EQ(known_sequence(Timer::Mode::min).Ticks(), 20u);
}

TEST(Timer, MaxModeKeepsTheLongestLap) {
  EXPECT_EQ(known_sequence(Timer::Mode::max).Ticks(), 100u);
}

TEST(Timer, AvgModeIsSumOverLaps) {
  const Timer t = known_sequence(Timer::Mode::avg);
  EXPECT_EQ(t.Ticks(), 50u);
  EXPECT_EQ(t.Laps(), 4u);
  EXPECT_EQ(t.Last(), 20u);
  // Every mode can be read whatever the timer's own mode.
  EXPECT_EQ(t.Ticks(Timer::Mode::sum), 200u);
  EXPECT_EQ(t.Ticks(Timer::Mode::min), 20u);
}

TEST(Timer, NoLapsReadsZeroInEveryMode) {
  const Timer t(Timer::Mode::min, 1e9);
  for (auto m : {Timer::Mode::sum, Timer::Mode::min, Timer::Mode::max, Timer::Mode::avg})
    EXPECT_EQ(t.Ticks(m), 0u);
}

TEST(Timer, ResetForgetsLapsButKeepsModeAndFrequency) {
  Timer t = known_sequence(Timer::Mode::min);
  t.Reset();
  EXPECT_EQ(t.Laps(), 0u);
  EXPECT_EQ(t.Ticks(), 0u);
  t.Record(70);
  t.Record(90);
  EXPECT_EQ(t.Ticks(), 70u);  // min after reset does not remember the old 20
  EXPECT_EQ(t.GetMode(), Timer::Mode::min);
  EXPECT_EQ(t.Frequency(), 1e9);
}

// Without rdtscp the timer counts steady_clock's nanoseconds whatever frequency it is given.
TEST(Timer, ExplicitFrequencyConvertsTicksToSeconds) {
  Timer t(Timer::Mode::sum, 2.5e9);
  t.Record(5'000'000'000ull);
  EXPECT_DOUBLE_EQ(t.Frequency(), Timer::HasRdtscp() ? 2.5e9 : 1e9);
  EXPECT_DOUBLE_EQ(t.Seconds(), Timer::HasRdtscp() ? 2.0 : 5.0);
  EXPECT_THROW(Timer(Timer::Mode::sum, 0.0), std::invalid_argument);
  EXPECT_THROW(Timer(Timer::Mode::sum, -1.0), std::invalid_argument);
}

TEST(Timer, CalibratedTimerAgreesWithSteadyClockWithin5PercentOver50ms) {
  Timer t;  // calibrates (or falls back to steady_clock)
  ASSERT_GT(t.Frequency(), 1e6);
  const auto w0 = std::chrono::steady_clock::now();
  t.Start();
  spin_for(50ms);
  t.Stop();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
  EXPECT_NEAR(t.Seconds(), wall, 0.05 * wall);
}

TEST(Timer, CalibrationIsStableAcrossRuns) {
  if (!Timer::HasRdtscp()) GTEST_SKIP() << "no rdtscp: calibration is not used";
  const double a = Timer::Calibrate(20ms), b = Timer::Calibrate(20ms);
  EXPECT_NEAR(a, b, 0.05 * a);
}

TEST(Timer, SteadyClockModeMeasuresElapsedNanoseconds) {
  Timer t(Timer::Mode::sum, Timer::Clock::steady);
  EXPECT_TRUE(t.UsesSteadyClock());
  EXPECT_EQ(t.Frequency(), 1e9);
  t.Start();
  std::this_thread::sleep_for(5ms);
  t.Stop();
  EXPECT_GE(t.Ticks(), 5'000'000u);
  EXPECT_LT(t.Seconds(), 5.0);  // sanity, not a timing threshold on the code under test
}

TEST(Timer, StartStopLapsAreCountedAndOrdered) {
  Timer t(Timer::Mode::max, 1e9);
  for (int i = 0; i < 100; ++i) {
    t.Start();
    t.Stop();
  }
  EXPECT_EQ(t.Laps(), 100u);
  EXPECT_GE(t.Ticks(Timer::Mode::max), t.Ticks(Timer::Mode::avg));
  EXPECT_GE(t.Ticks(Timer::Mode::avg), t.Ticks(Timer::Mode::min));
}

}  // namespace
}  // namespace mlib
