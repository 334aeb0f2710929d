// mlib::set_flush_denormals: FTZ flushes denormal results, DAZ reads denormal inputs as 0,
// and the previous mode is reported so that it can be restored.
#include "mlib/fpmode.h"

#include <gtest/gtest.h>

namespace mlib {
namespace {

// Restores the thread's mode when a test ends, whatever it asserted.
struct RestoreMode {
  bool was = flush_denormals();
  ~RestoreMode() { set_flush_denormals(was); }
};

TEST(FpMode, FlushToZeroTurnsADenormalResultIntoZero) {
  RestoreMode restore;
  volatile float a = 1e-30f, b = 1e-10f;  // a * b = 1e-40 is below FLT_MIN (1.2e-38)
  set_flush_denormals(false);
  EXPECT_GT(a * b, 0.0f);
  set_flush_denormals(true);
  EXPECT_EQ(a * b, 0.0f);
}

TEST(FpMode, DenormalsAreZeroReadsADenormalInputAsZero) {
  RestoreMode restore;
  set_flush_denormals(false);
  volatile float d = 1e-30f;
  d = d * 1e-10f;  // a denormal, made while denormals are kept
  volatile float big = 1e30f;
  EXPECT_GT(d * big, 1e-11f);  // 1e-10: a normal result from a denormal input
  set_flush_denormals(true);
  EXPECT_EQ(d * big, 0.0f);
}

TEST(FpMode, SetFlushDenormalsReturnsThePreviousMode) {
  RestoreMode restore;
  set_flush_denormals(false);
  EXPECT_FALSE(flush_denormals());
  EXPECT_FALSE(set_flush_denormals(true));
  EXPECT_TRUE(flush_denormals());
  EXPECT_TRUE(set_flush_denormals(false));
  EXPECT_FALSE(flush_denormals());
}

}  // namespace
}  // namespace mlib
