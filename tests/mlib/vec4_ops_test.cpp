// Every vec4 operation against a plain scalar reference on fixed-seed random inputs.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <random>
#include <vector>

#include "mlib/vec4_functions.h"
#include "tests/mlib/reference.h"

namespace mlib::test {

#if !defined(MLIB_SCALAR)
void dot_avx2(const float* a, const float* b, float* out, int n);  // dot_avx2_checks.cpp
#endif

namespace {

constexpr std::size_t kN = 2000;

// Checks that `vec_op(a, b)` equals `lane_op(a_i, b_i)` bit for bit in every lane.
template <class VecOp, class LaneOp>
void expect_lanewise(VecOp vec_op, LaneOp lane_op, unsigned seed) {
  const auto as = random_refs(kN, seed), bs = random_refs(kN, seed + 1);
  for (std::size_t k = 0; k < kN; ++k) {
    const vec4 r = vec_op(make(as[k]), make(bs[k]));
    for (int i = 0; i < 4; ++i)
      ASSERT_TRUE(same_bits(r[i], lane_op(as[k][i], bs[k][i])))
          << "k=" << k << " lane " << i << ": " << r[i];
  }
}

TEST(Vec4Construct, DefaultIsAllZeroBits) {
  const vec4 v;
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(same_bits(v[i], 0.0f));
  const vec4 z = vec4::zero();
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(same_bits(z[i], 0.0f));
}

TEST(Vec4Construct, FourFloatsKeepLaneOrder) {
  const vec4 v(1.0f, 2.0f, 3.0f, 4.0f);
  EXPECT_EQ(v[0], 1.0f);
  EXPECT_EQ(v[1], 2.0f);
  EXPECT_EQ(v[2], 3.0f);
  EXPECT_EQ(v[3], 4.0f);
  EXPECT_EQ(v.x(), 1.0f);
  EXPECT_EQ(v.y(), 2.0f);
  EXPECT_EQ(v.z(), 3.0f);
  EXPECT_EQ(v.w(), 4.0f);
}

TEST(Vec4Construct, ThreeFloatsSetWToZero) {
  const vec4 v(1.0f, 2.0f, 3.0f);
  EXPECT_TRUE(same_bits(v[3], 0.0f));
}

TEST(Vec4Construct, OneFloatBroadcasts) {
  const vec4 v(7.5f);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(v[i], 7.5f);
}

TEST(Vec4Construct, LoadsFromUnalignedPointer) {
  alignas(16) float buf[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  const vec4 v(buf + 1);  // deliberately misaligned by 4 bytes
  for (int i = 0; i < 4; ++i) EXPECT_EQ(v[i], float(i + 1));
}

TEST(Vec4Construct, M128RoundTripsAndStoreWritesAllLanes) {
  // Through mlib::simd rather than _mm_ intrinsics, so it also runs in the scalar build.
  const simd::f4 m = simd::setr(-1.0f, 0.5f, 1e30f, -0.0f);
  const vec4 v(m);
  float out[4];
  v.store(out);
  EXPECT_EQ(out[0], -1.0f);
  EXPECT_EQ(out[1], 0.5f);
  EXPECT_EQ(out[2], 1e30f);
  EXPECT_TRUE(same_bits(out[3], -0.0f));
  const simd::f4 back = v.m128();
  EXPECT_EQ(simd::movemask(simd::cmp_eq(back, m)), 0xF);
}

TEST(Vec4Construct, CopyAndAssignPreserveBits) {
  const vec4 a(std::nanf(""), -0.0f, 1e-40f, -3.0f);
  const vec4 b(a);
  vec4 c;
  c = a;
  for (int i = 0; i < 4; ++i) {
    EXPECT_TRUE(same_bits(b[i], a[i]));
    EXPECT_TRUE(same_bits(c[i], a[i]));
  }
}

TEST(Vec4Construct, SetOverwritesEveryLane) {
  vec4 v(9.0f);
  v.set(1.0f, -2.0f, 3.0f, -4.0f);
  EXPECT_EQ(ref(v), (Ref{1.0f, -2.0f, 3.0f, -4.0f}));
}

TEST(Vec4Construct, LaneWriteThroughIndexChangesOnlyThatLane) {
  vec4 v(1.0f, 2.0f, 3.0f, 4.0f);
  v[2] = -8.0f;
  EXPECT_EQ(ref(v), (Ref{1.0f, 2.0f, -8.0f, 4.0f}));
}

TEST(Vec4Arith, AddMatchesScalarReference) {
  expect_lanewise([](vec4 a, vec4 b) { return vec4(a + b); },
                  [](float a, float b) { return a + b; }, 1);
}

TEST(Vec4Arith, SubMatchesScalarReference) {
  expect_lanewise([](vec4 a, vec4 b) { return vec4(a - b); },
                  [](float a, float b) { return a - b; }, 2);
}

TEST(Vec4Arith, MulMatchesScalarReference) {
  expect_lanewise([](vec4 a, vec4 b) { return vec4(a * b); },
                  [](float a, float b) { return a * b; }, 3);
}

TEST(Vec4Arith, DivMatchesScalarReference) {
  expect_lanewise([](vec4 a, vec4 b) { return vec4(a / b); },
                  [](float a, float b) { return a / b; }, 4);
}

TEST(Vec4Arith, NegateFlipsOnlyTheSign) {
  expect_lanewise([](vec4 a, vec4) { return vec4(-a); }, [](float a, float) { return -a; },
                  5);
  const vec4 z = -vec4(0.0f);
  EXPECT_TRUE(same_bits(z[0], -0.0f));
}

TEST(Vec4Arith, ScalarsMixOnEitherSide) {
  expect_lanewise([](vec4 a, vec4) { return vec4(2.5f * a); },
                  [](float a, float) { return 2.5f * a; }, 6);
  expect_lanewise([](vec4 a, vec4) { return vec4(a * 2.5f); },
                  [](float a, float) { return a * 2.5f; }, 7);
  expect_lanewise([](vec4 a, vec4) { return vec4(a / 3.0f); },
                  [](float a, float) { return a / 3.0f; }, 8);
  expect_lanewise([](vec4 a, vec4) { return vec4(3.0f / a); },
                  [](float a, float) { return 3.0f / a; }, 9);
  expect_lanewise([](vec4 a, vec4) { return vec4(1 - a); },  // an int mixes in too
                  [](float a, float) { return 1.0f - a; }, 10);
  expect_lanewise([](vec4 a, vec4) { return vec4(a + 0.25); },  // and a double
                  [](float a, float) { return a + 0.25f; }, 11);
}

TEST(Vec4Compound, PlusEqualsAcceptsVectorsScalarsAndExpressions) {
  expect_lanewise(
      [](vec4 a, vec4 b) {
        a += b;
        a += 1.0f;
        a += b * 2.0f;
        return a;
      },
      [](float a, float b) { return ((a + b) + 1.0f) + b * 2.0f; }, 12);
}

TEST(Vec4Compound, MinusEqualsAcceptsVectorsScalarsAndExpressions) {
  expect_lanewise(
      [](vec4 a, vec4 b) {
        a -= b;
        a -= 1.0f;
        a -= b * 2.0f;
        return a;
      },
      [](float a, float b) { return ((a - b) - 1.0f) - b * 2.0f; }, 13);
}

TEST(Vec4Compound, TimesEqualsAcceptsVectorsScalarsAndExpressions) {
  expect_lanewise(
      [](vec4 a, vec4 b) {
        a *= b;
        a *= 0.5f;
        a *= b + 1.0f;
        return a;
      },
      [](float a, float b) { return ((a * b) * 0.5f) * (b + 1.0f); }, 14);
}

TEST(Vec4Compound, DivideEqualsAcceptsVectorsScalarsAndExpressions) {
  expect_lanewise(
      [](vec4 a, vec4 b) {
        a /= b;
        a /= 4.0f;
        a /= b * b;
        return a;
      },
      [](float a, float b) { return ((a / b) / 4.0f) / (b * b); }, 15);
}

TEST(Vec4Functions, DotIsWithinRoundingBoundOfDoubleReference) {
  const auto as = random_refs(kN, 20), bs = random_refs(kN, 21);
  for (std::size_t k = 0; k < kN; ++k) {
    const float d = dot(make(as[k]), make(bs[k]));
    ASSERT_NEAR(d, dot_ref(as[k], bs[k]), dot_bound(as[k], bs[k])) << k;
  }
}

TEST(Vec4Functions, DotUsedAsVectorIsBroadcast) {
  const vec4 a(1, 2, 3, 4), b(5, 6, 7, 8);
  const vec4 d = dot(a, b);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(d[i], 70.0f);
}

TEST(Vec4Functions, CrossMatchesReferenceAndIsOrthogonal) {
  const auto as = random_refs(kN, 22), bs = random_refs(kN, 23);
  for (std::size_t k = 0; k < kN; ++k) {
    Ref a = as[k], b = bs[k];
    a[3] = b[3] = 0.0f;
    const vec4 c = cross(make(a), make(b));
    const float rx = a[1] * b[2] - a[2] * b[1];
    const float ry = a[2] * b[0] - a[0] * b[2];
    const float rz = a[0] * b[1] - a[1] * b[0];
    ASSERT_TRUE(same_bits(c[0], rx) && same_bits(c[1], ry) && same_bits(c[2], rz)) << k;
    ASSERT_EQ(c[3], 0.0f);
    // Orthogonality, relative to the magnitudes involved.
    const double scale = std::sqrt(dot_ref(a, a) * dot_ref(b, b));
    EXPECT_LE(std::fabs(dot_ref(ref(c), a)), 1e-5 * scale * std::sqrt(dot_ref(a, a)));
  }
}

TEST(Vec4Functions, NormalizeGivesUnitLengthAndSameDirection) {
  const auto as = random_refs(kN, 24);
  for (std::size_t k = 0; k < kN; ++k) {
    const vec4 a = make(as[k]);
    const vec4 n = normalize(a);
    vec4 m = a;
    m.normalize();
    const double len = std::sqrt(dot_ref(ref(n), ref(n)));
    ASSERT_NEAR(len, 1.0, 4e-7) << k;
    const double inv = 1.0 / std::sqrt(dot_ref(as[k], as[k]));
    for (int i = 0; i < 4; ++i) {
      ASSERT_NEAR(n[i], as[k][i] * inv, 4e-7) << k;
      ASSERT_TRUE(same_bits(m[i], n[i]));  // member and free function agree
    }
  }
}

TEST(Vec4Functions, AbsClearsOnlyTheSignBit) {
  expect_lanewise([](vec4 a, vec4) { return vec4(abs(a)); },
                  [](float a, float) { return std::fabs(a); }, 25);
}

TEST(Vec4Functions, SqrtIsLanewise) {
  expect_lanewise([](vec4 a, vec4) { return vec4(sqrt(abs(a))); },
                  [](float a, float) { return std::sqrt(std::fabs(a)); }, 26);
}

TEST(Vec4Functions, MinAndMaxAreLanewise) {
  expect_lanewise([](vec4 a, vec4 b) { return vec4(min(a, b)); },
                  [](float a, float b) { return a < b ? a : b; }, 27);
  expect_lanewise([](vec4 a, vec4 b) { return vec4(max(a, b)); },
                  [](float a, float b) { return a > b ? a : b; }, 28);
}

TEST(Vec4Functions, ClampBoundsEveryLane) {
  expect_lanewise([](vec4 a, vec4) { return vec4(clamp(a, -1.0f, 2.0f)); },
                  [](float a, float) { return a < -1.0f ? -1.0f : (a > 2.0f ? 2.0f : a); },
                  29);
  expect_lanewise(
      [](vec4 a, vec4) {
        a.clamp(-1.0f, 2.0f);
        return a;
      },
      [](float a, float) { return a < -1.0f ? -1.0f : (a > 2.0f ? 2.0f : a); }, 30);
}

TEST(Vec4Functions, CalcDistanceMatchesDoubleReference) {
  const auto as = random_refs(kN, 31), bs = random_refs(kN, 32);
  for (std::size_t k = 0; k < kN; ++k) {
    Ref d;
    for (int i = 0; i < 4; ++i) d[i] = as[k][i] - bs[k][i];
    const double expected = std::sqrt(dot_ref(d, d));
    ASSERT_NEAR(calc_distance(make(as[k]), make(bs[k])), expected, 4e-7 * expected) << k;
  }
}

TEST(Vec4Functions, ToColorPacksRoundedClampedChannels) {
  EXPECT_EQ(to_color(vec4(1.0f, 0.0f, 0.5f)), 0xFF0080u);  // 127.5 rounds to even: 128
  EXPECT_EQ(to_color(vec4(2.0f, -1.0f, 0.2f)), 0xFF0033u);  // 51.0
  EXPECT_EQ(to_color(vec4(0.1f, 0.9f, 1.0f, 7.0f)), 0x1AE6FFu);
  std::mt19937 rng(33);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int k = 0; k < 1000; ++k) {
    const float r = u(rng), g = u(rng), b = u(rng);
    const auto expect = [](float c) { return std::uint32_t(std::nearbyint(c * 255.0f)); };
    ASSERT_EQ(to_color(vec4(r, g, b)), (expect(r) << 16) | (expect(g) << 8) | expect(b));
  }
}

TEST(Vec4Functions, TruncateClampEqualsTheScalarCastClampedAndSendsNanAndHugeToLo) {
  std::int32_t k[4];
  truncate_clamp(vec4(2.99f, -0.99f, -1.5f, 16.0f), 0, 15, k);
  EXPECT_EQ(k[0], 2);   // toward zero
  EXPECT_EQ(k[1], 0);   // -0.99 truncates to 0
  EXPECT_EQ(k[2], 0);   // -1 clamped up
  EXPECT_EQ(k[3], 15);  // clamped down
  // From memory the compiler cannot see into: folded at compile time, GCC saturates
  // instead of giving the instruction's integer indefinite.
  volatile float odd[4] = {std::nanf(""), 3.0e9f, -3.0e9f, INFINITY};
  truncate_clamp(vec4(odd[0], odd[1], odd[2], odd[3]), -4, 7, k);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(k[i], -4) << i;  // no int32: the integer indefinite
  std::mt19937 rng(34);
  std::uniform_real_distribution<float> u(-40.0f, 40.0f);
  for (int n = 0; n < 1000; ++n) {
    const vec4 v(u(rng), u(rng), u(rng), u(rng));
    truncate_clamp(v * 1.0f, -8, 31, k);  // an expression, as callers pass
    for (int i = 0; i < 4; ++i)
      ASSERT_EQ(k[i], std::clamp(static_cast<std::int32_t>(v[i]), -8, 31)) << v[i];
  }
}

// simd::step_ulps against the integer formula written lane by lane: bits + trunc(k), or
// bits - trunc(k) where a < 0 (-0 counts as not negative), the cast's integer indefinite
// (INT32_MIN) for NaN and k beyond int32, wrapping at the ends of the bit patterns.
TEST(Simd, StepUlpsEqualsTheBitFormulaLaneByLaneAtSignsZerosNanAndWrapping) {
  const auto oracle = [](float a, float k) {
    const std::int32_t steps =
        k >= -2147483648.0f && k < 2147483648.0f ? static_cast<std::int32_t>(k) : INT32_MIN;
    const auto u = static_cast<std::uint32_t>(steps);
    return std::bit_cast<float>(std::bit_cast<std::uint32_t>(a) + (a < 0.0f ? 0u - u : u));
  };
  const auto check = [&](float a0, float a1, float a2, float a3, float k0, float k1, float k2,
                         float k3) {
    const float a[4] = {a0, a1, a2, a3}, k[4] = {k0, k1, k2, k3};
    float out[4];
    simd::store(out, simd::step_ulps(simd::load(a), simd::load(k)));
    for (int i = 0; i < 4; ++i)
      ASSERT_TRUE(same_bits(out[i], oracle(a[i], k[i]))) << a[i] << " " << k[i] << " -> " << out[i];
  };
  // From memory the compiler cannot see into (folded, GCC would saturate the cast).
  volatile float v[] = {std::nanf(""), 3.0e9f, -3.0e9f, INFINITY, -INFINITY, -0.0f, 0.0f,
                        std::numeric_limits<float>::max(), -std::numeric_limits<float>::max(),
                        std::numeric_limits<float>::denorm_min(), 255.9f, -255.9f};
  const int n = sizeof v / sizeof v[0];
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) check(v[i], v[j], -v[i], 1.0f, v[j], 7.5f, -v[j], v[i]);
  EXPECT_EQ(std::bit_cast<std::uint32_t>(oracle(1.0f, 1.0f)), 0x3f800001u);  // one float up
  EXPECT_EQ(oracle(-1.0f, 1.0f), std::nextafter(-1.0f, 0.0f));  // towards +inf, as 1's
  std::mt19937 rng(35);
  std::uniform_real_distribution<float> u(-300.0f, 300.0f);
  std::uniform_real_distribution<float> e(-40.0f, 40.0f);
  for (int r = 0; r < 10000; ++r) {
    const auto x = [&] { return std::ldexp(u(rng), int(e(rng))); };
    check(x(), x(), x(), x(), u(rng), u(rng), u(rng), u(rng));
  }
}

// The wide units' dot product (simd.h: multiply, two shuffle-adds) against the baseline's
// dpps: the same bits in all four lanes (NaN where dpps gives NaN), over every pairing of
// signed zeros, denormals, overflowing and cancelling products, infinities and NaN, and
// random vectors.
TEST(Simd, WideUnitsDotProductEqualsDppsBitForBitInEveryLane) {
#if defined(MLIB_SCALAR)
  GTEST_SKIP() << "the scalar build has no AVX2 unit";
#else
  if (!__builtin_cpu_supports("avx2")) GTEST_SKIP() << "this CPU has no AVX2";
  const float odd[] = {0.0f, -0.0f, 1.0f, -1.0f, 1e-30f, -1e-30f, 1e-40f, 3e38f, -3e38f,
                       INFINITY, -INFINITY, std::nanf(""), 0.1f, 1e20f, -1e20f, 7.0f};
  const int n_odd = sizeof odd / sizeof odd[0];
  std::vector<float> a, b;
  std::mt19937 rng(37);
  std::uniform_int_distribution<int> pick(0, n_odd - 1);
  for (int i = 0; i < 200000; ++i)
    for (int l = 0; l < 4; ++l) {
      a.push_back(odd[pick(rng)]);
      b.push_back(odd[pick(rng)]);
    }
  for (const Ref& r : random_refs(20000, 38))
    for (int l = 0; l < 4; ++l) a.push_back(r[l]);
  for (const Ref& r : random_refs(20000, 39))
    for (int l = 0; l < 4; ++l) b.push_back(r[l]);
  const int n = int(a.size() / 4);
  std::vector<float> wide(a.size());
  dot_avx2(a.data(), b.data(), wide.data(), n);
  for (int i = 0; i < n; ++i) {
    float base[4];
    simd::store(base, simd::dp_bcast(simd::load(&a[4 * i]), simd::load(&b[4 * i])));
    for (int l = 0; l < 4; ++l) {
      const float w = wide[4 * i + l];
      ASSERT_TRUE(std::isnan(base[l]) ? std::isnan(w) : same_bits(w, base[l]))
          << "vector " << i << " lane " << l << ": " << w << " vs dpps " << base[l];
    }
  }
#endif
}

TEST(Vec4Functions, StrPrintsAllLanesAndRoundTrips) {
  const vec4 v(0.1f, -2.5f, 1e-30f, 3.0e38f);
  const std::string s = str(v);
  EXPECT_EQ(s.front(), '(');
  float back[4];
  ASSERT_EQ(std::sscanf(s.c_str(), "(%g, %g, %g, %g)", &back[0], &back[1], &back[2], &back[3]),
            4);
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(same_bits(back[i], v[i])) << s;
  EXPECT_EQ(str(v + v), str(vec4(v + v)));  // accepts expressions
}

TEST(Vec4Alignment, ArrayElementsAre16ByteAligned) {
  vec4 arr[7];
  for (const vec4& v : arr) EXPECT_EQ(reinterpret_cast<std::uintptr_t>(&v) % 16, 0u);
  struct Holder {
    char c;
    vec4 v;
  };
  static_assert(alignof(Holder) == 16 && offsetof(Holder, v) == 16);
  EXPECT_EQ(sizeof(arr), 7 * 16u);
}

TEST(Vec4Alignment, StdVectorStorageIs16ByteAligned) {
  for (std::size_t n : {1u, 3u, 17u, 1000u}) {
    std::vector<vec4> v(n, vec4(1.0f));
    v.push_back(vec4(2.0f));
    for (const vec4& e : v) ASSERT_EQ(reinterpret_cast<std::uintptr_t>(&e) % 16, 0u);
  }
  auto* heap = new vec4[5];
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(heap) % 16, 0u);
  delete[] heap;
}

}  // namespace
}  // namespace mlib::test
