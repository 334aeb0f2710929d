// vec4 at the numerical edges: NaN, ±infinity, ±0, denormals, 1e-30 and 1e30, and the
// all-lanes comparison semantics. Each test names the documented behaviour it checks.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "mlib/vec4_functions.h"
#include "tests/mlib/reference.h"

namespace mlib::test {
namespace {

const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();
const float kDenorm = 1e-40f;  // below FLT_MIN = 1.18e-38

bool all_nan(const vec4& v) {
  for (int i = 0; i < 4; ++i)
    if (!std::isnan(v[i])) return false;
  return true;
}

TEST(Vec4Edge, DotPropagatesNaN) {
  EXPECT_TRUE(std::isnan(float(dot(vec4(kNaN, 0, 0), vec4(1, 1, 1)))));
  EXPECT_TRUE(std::isnan(float(dot(vec4(1, 1, 1), vec4(0, 0, kNaN)))));
}

TEST(Vec4Edge, DotWithInfinityFollowsIeee) {
  EXPECT_EQ(float(dot(vec4(kInf, 1, 0), vec4(1, 1, 0))), kInf);
  EXPECT_EQ(float(dot(vec4(-kInf, 0, 0), vec4(2, 0, 0))), -kInf);
  EXPECT_TRUE(std::isnan(float(dot(vec4(kInf, 0, 0), vec4(0, 1, 0)))));  // inf * 0
  EXPECT_TRUE(std::isnan(float(dot(vec4(kInf, kInf, 0), vec4(1, -1, 0)))));  // inf - inf
}

TEST(Vec4Edge, DotOfSignedZerosIsZero) {
  const float d = dot(vec4(-0.0f, 0.0f, -0.0f, 0.0f), vec4(1, -1, 1, -1));
  EXPECT_EQ(d, 0.0f);
}

TEST(Vec4Edge, DenormalsAreKeptNotFlushed) {
  const float d = dot(vec4(kDenorm, 0, 0), vec4(1, 0, 0));
  EXPECT_EQ(d, kDenorm);
  const vec4 s = vec4(kDenorm) + vec4(kDenorm);
  EXPECT_EQ(s[0], 2 * kDenorm);
}

TEST(Vec4Edge, DotOverflowsToInfinityForComponentsOf1e30) {
  // 1e30 * 1e30 = 1e60 > FLT_MAX: the documented behaviour is +inf, never a wrapped value.
  EXPECT_EQ(float(dot(vec4(1e30f, 0, 0), vec4(1e30f, 0, 0))), kInf);
  EXPECT_EQ(float(dot(vec4(2e19f, 2e19f, 0), vec4(2e19f, 2e19f, 0))), kInf);  // 8e38
  // Mixed magnitudes that stay in range are exact: 1e30 * 1e-30 = 1 (to rounding).
  EXPECT_NEAR(float(dot(vec4(1e30f, 0, 0), vec4(1e-30f, 0, 0))), 1.0f, 1e-6f);
}

TEST(Vec4Edge, DotUnderflowsToZeroForComponentsOf1eMinus30) {
  EXPECT_EQ(float(dot(vec4(1e-30f, 1e-30f, 1e-30f), vec4(1e-30f, 1e-30f, 1e-30f))), 0.0f);
}

TEST(Vec4Edge, NormalizeOfZeroIsZeroNotNaN) {
  const vec4 z = normalize(vec4(0.0f));
  EXPECT_EQ(ref(z), (Ref{0, 0, 0, 0}));
  const vec4 nz = normalize(vec4(-0.0f, 0.0f, -0.0f));
  EXPECT_FALSE(std::isnan(nz[0]));
  EXPECT_EQ(nz, vec4(0.0f));
  vec4 m(0.0f);
  m.normalize();
  EXPECT_EQ(m, vec4(0.0f));
}

TEST(Vec4Edge, NormalizeWithNaNOrInfinityIsAllNaN) {
  EXPECT_TRUE(all_nan(normalize(vec4(kNaN, 1, 0))));
  EXPECT_TRUE(all_nan(normalize(vec4(kInf, 1, 0))));
  EXPECT_TRUE(all_nan(normalize(vec4(0, -kInf, 0))));
}

TEST(Vec4Edge, NormalizeIsUnitForHugeTinyAndDenormalVectors) {
  for (float s : {1e30f, 8e37f, 1e19f, 1e-19f, 1e-30f, kDenorm, 1e-45f}) {
    const vec4 n = normalize(vec4(3 * s, -4 * s, 0));
    if (s == 1e-45f) {  // the smallest denormal: 3s and 4s are themselves rounded
      EXPECT_NEAR(float(dot(n, n)), 1.0f, 1e-6f);
      continue;
    }
    EXPECT_NEAR(n[0], 0.6f, 2e-7f) << s;
    EXPECT_NEAR(n[1], -0.8f, 2e-7f) << s;
    EXPECT_EQ(n[2], 0.0f) << s;
  }
}

TEST(Vec4Edge, CrossOfHugeVectorsOverflowsToInfinity) {
  const vec4 c = cross(vec4(1e30f, 0, 0), vec4(0, 1e30f, 0));
  EXPECT_EQ(c[2], kInf);
  EXPECT_EQ(c[0], 0.0f);
  EXPECT_EQ(c[1], 0.0f);
}

TEST(Vec4Edge, CrossOfTinyVectorsUnderflowsToZeroAndNormalizeCannotRecoverIt) {
  const vec4 c = cross(vec4(1e-30f, 0, 0), vec4(0, 1e-30f, 0));
  EXPECT_EQ(c, vec4(0.0f));  // 1e-60 is below the smallest denormal
  // Scaling before the cross product keeps the direction: the caller's job.
  const vec4 d = normalize(cross(vec4(1e-30f, 0, 0) * 1e30f, vec4(0, 1e-30f, 0) * 1e30f));
  EXPECT_EQ(d, vec4(0, 0, 1));
}

TEST(Vec4Edge, CrossWithNaNGivesNaNInDependentLanes) {
  const vec4 c = cross(vec4(kNaN, 0, 0), vec4(0, 1, 0));
  EXPECT_TRUE(std::isnan(c[2]));  // z = ax*by - ay*bx
  EXPECT_TRUE(std::isnan(c[1]));  // y = az*bx - ax*bz: NaN * 0
}

TEST(Vec4Edge, CrossOfParallelVectorsIsZero) {
  EXPECT_EQ(cross(vec4(1, 2, 3), vec4(2, 4, 6)), vec4(0.0f));
}

TEST(Vec4Compare, OrderingHoldsOnlyWhenTrueInAllLanes) {
  const vec4 a(1, 2, 3, 4), b(2, 3, 4, 5), c(0, 3, 4, 5);
  EXPECT_TRUE(a < b);
  EXPECT_TRUE(b > a);
  EXPECT_TRUE(a <= b && a <= a && a >= a);
  EXPECT_FALSE(a < c);   // lane 0 fails
  EXPECT_FALSE(c < a);   // lanes 1..3 fail
  EXPECT_FALSE(a > c);
  EXPECT_FALSE(a >= c);
  EXPECT_TRUE(a == vec4(1, 2, 3, 4));
  EXPECT_TRUE(a != c);
}

TEST(Vec4Compare, NaNMakesOrderedComparisonsFalseAndNotEqualTrue) {
  const vec4 n(kNaN, 1, 1, 1), one(1.0f);
  EXPECT_FALSE(n == n);
  EXPECT_TRUE(n != n);
  EXPECT_FALSE(n < vec4(2.0f));
  EXPECT_FALSE(n <= vec4(2.0f));
  EXPECT_FALSE(n > vec4(0.0f));
  EXPECT_FALSE(n >= vec4(0.0f));
  EXPECT_TRUE(n != one);
}

TEST(Vec4Compare, SignedZerosCompareEqual) {
  EXPECT_TRUE(vec4(0.0f) == vec4(-0.0f));
  EXPECT_FALSE(vec4(0.0f) < vec4(-0.0f));
}

TEST(Vec4Compare, ScalarOperandsAreBroadcast) {
  const vec4 a(1, 2, 3, 4);
  EXPECT_TRUE(a > 0.5f);
  EXPECT_FALSE(a > 1.5f);
  EXPECT_TRUE(0 < a);
  EXPECT_TRUE(dot(a, a) > 29.0f);  // 30 in all lanes
  EXPECT_TRUE(dot(a, a) == 30.0f);
  EXPECT_FALSE(dot(a, -a) >= 0.0f);
}

}  // namespace
}  // namespace mlib::test
