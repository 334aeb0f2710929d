// The wide SIMD types: vfloat4 (SSE4.1, or plain C++ in the scalar build) and, on a CPU with
// AVX2, vfloat8, and on one with AVX-512, vfloat16 — arithmetic, masks, NaN rules, sign tricks and the integer order of bits
// that the BVH's node test relies on (vfloat_checks.h).
#include <gtest/gtest.h>

#include "tests/mlib/vfloat_checks.h"

namespace mlib::test {
int check_vfloat8(char (&first)[kFirstFailureSize]);   // vfloat8_checks.cpp
int check_vfloat16(char (&first)[kFirstFailureSize]);  // vfloat16_checks.cpp
int check_compress_in_order_avx2(char (&first)[kFirstFailureSize]);    // vfloat8_checks.cpp
int check_compress_in_order_avx512(char (&first)[kFirstFailureSize]);  // vfloat16_checks.cpp
namespace {

TEST(Vfloat, FourLanesFollowIeeeAndTheDocumentedMaskAndNaNRules) {
  char first[kFirstFailureSize];
  EXPECT_EQ(check_vfloat<vfloat4>(first), 0) << "first failure: " << first;
}

#if !defined(MLIB_SCALAR)
TEST(Vfloat, EightLanesFollowTheSameRulesOnAnAvx2Cpu) {
  if (!__builtin_cpu_supports("avx2")) GTEST_SKIP() << "this CPU has no AVX2";
  char first[kFirstFailureSize];
  EXPECT_EQ(check_vfloat8(first), 0) << "first failure: " << first;
}

TEST(Vfloat, SixteenLanesFollowTheSameRulesOnAnAvx512Cpu) {
  if (!__builtin_cpu_supports("avx512f")) GTEST_SKIP() << "this CPU has no AVX-512";
  char first[kFirstFailureSize];
  EXPECT_EQ(check_vfloat16(first), 0) << "first failure: " << first;
}

TEST(Vfloat, CompressInOrderEqualsThePlainLoopForEveryMaskAndOctantWithAvx2AndAvx512For8And16Lanes) {
  if (!__builtin_cpu_supports("avx2")) GTEST_SKIP() << "this CPU has no AVX2";
  char first[kFirstFailureSize];
  EXPECT_EQ(check_compress_in_order_avx2(first), 0) << "AVX2: " << first;
  // vfloat16_checks.cpp is built with AVX-512 F, VL, DQ and CD
  if (!__builtin_cpu_supports("avx512f") || !__builtin_cpu_supports("avx512vl") ||
      !__builtin_cpu_supports("avx512dq") || !__builtin_cpu_supports("avx512cd"))
    return;
  EXPECT_EQ(check_compress_in_order_avx512(first), 0) << "AVX-512: " << first;
}
#endif

}  // namespace
}  // namespace mlib::test
