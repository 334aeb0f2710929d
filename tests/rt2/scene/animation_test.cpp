// rt2/scene/animation.h: keyframe tracks against oracles written another way, in long double:
// linear interpolation, slerp as q0 (q0* q1)^u through the axis and angle, cubic splines
// against the cubic polynomial their keys and tangents come from, and T * R * S against
// rotating points by the quaternion sandwich q p q*. Each test names the property it checks.
#include "rt2/scene/animation.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace rt2 {
namespace {

using Quat = std::array<long double, 4>;  // x y z w

Quat multiply(const Quat& a, const Quat& b) {
  return {a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1],
          a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0],
          a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3],
          a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2]};
}

Quat conjugate(const Quat& q) { return {-q[0], -q[1], -q[2], q[3]}; }

Quat normalized(Quat q) {
  const long double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (long double& c : q) c /= n;
  return q;
}

// q0 (q0* q1)^u along the shorter arc, the power taken through the axis and the angle.
Quat slerp_oracle(Quat q0, Quat q1, long double u) {
  q0 = normalized(q0);
  q1 = normalized(q1);
  if (q0[0] * q1[0] + q0[1] * q1[1] + q0[2] * q1[2] + q0[3] * q1[3] < 0)
    for (long double& c : q1) c = -c;
  const Quat r = multiply(conjugate(q0), q1);
  const long double s = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
  if (s == 0) return q0;
  const long double half = std::atan2(s, r[3]) * u;
  const Quat p = {r[0] / s * std::sin(half), r[1] / s * std::sin(half), r[2] / s * std::sin(half),
                  std::cos(half)};
  return multiply(q0, p);
}

// The distance between two rotations given as unit quaternions (q and -q are one rotation).
double rotation_distance(const double* a, const Quat& b) {
  long double d = 0;
  for (int k = 0; k < 4; ++k) d += a[k] * b[k];
  return double(1 - std::fabs(d));
}

Track make_track(NodeProperty property, Interpolation interpolation, std::vector<double> times,
                 std::vector<double> values) {
  Track t;
  t.property = property;
  t.interpolation = interpolation;
  t.times = std::move(times);
  t.values = std::move(values);
  t.width = key_width(property, 2);
  return t;
}

TEST(Animation, StepHoldsEachKeyUntilTheNext) {
  const Track t = make_track(NodeProperty::translation, Interpolation::step, {0.0, 1.0, 2.5},
                             {1, 2, 3, 4, 5, 6, 7, 8, 9});
  double out[3];
  for (const auto& [seconds, key] :
       std::vector<std::pair<double, int>>{{0.0, 0}, {0.999, 0}, {1.0, 1}, {2.4999, 1}, {2.5, 2}}) {
    sample(t, seconds, out);
    EXPECT_EQ(out[0], 1 + 3 * key) << seconds;
    EXPECT_EQ(out[2], 3 + 3 * key) << seconds;
  }
}

TEST(Animation, LinearTranslationEqualsTheLongDoubleLerp) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> value(-1e3, 1e3), gap(1e-3, 2.0);
  std::vector<double> times{gap(rng)}, values;
  for (int k = 1; k < 20; ++k) times.push_back(times.back() + gap(rng));
  for (std::size_t i = 0; i < times.size() * 3; ++i) values.push_back(value(rng));
  const Track t = make_track(NodeProperty::scale, Interpolation::linear, times, values);
  for (int i = 0; i < 2000; ++i) {
    const double seconds = times.front() + (times.back() - times.front()) * (i / 1999.0);
    double out[3];
    sample(t, seconds, out);
    std::size_t k = 0;
    while (k + 2 < times.size() && times[k + 1] <= seconds) ++k;
    const long double u = (seconds - (long double)times[k]) / (times[k + 1] - (long double)times[k]);
    for (int c = 0; c < 3; ++c) {
      const long double a = values[3 * k + c], b = values[3 * (k + 1) + c];
      EXPECT_NEAR(out[c], double(a + u * (b - a)), 1e-9) << "at " << seconds;
    }
  }
}

TEST(Animation, LinearRotationIsTheSlerpOfTheAxisAndAngleOracle) {
  std::mt19937 rng(11);
  std::normal_distribution<double> g;
  for (int pair = 0; pair < 200; ++pair) {
    const std::vector<double> keys = {g(rng), g(rng), g(rng), g(rng), g(rng), g(rng), g(rng), g(rng)};
    const Track t = make_track(NodeProperty::rotation, Interpolation::linear, {0.0, 1.0}, keys);
    const Quat q0 = {keys[0], keys[1], keys[2], keys[3]}, q1 = {keys[4], keys[5], keys[6], keys[7]};
    for (const double u : {0.0, 0.1, 0.25, 0.5, 0.77, 0.999, 1.0}) {
      double out[4];
      sample(t, u, out);
      EXPECT_LT(rotation_distance(out, slerp_oracle(q0, q1, u)), 1e-13) << pair << " " << u;
      EXPECT_NEAR(out[0] * out[0] + out[1] * out[1] + out[2] * out[2] + out[3] * out[3], 1.0, 1e-15);
    }
  }
}

TEST(Animation, RotationExtremesNearlyEqualOppositeAndOrthogonalKeys) {
  // Keys 1e-10 rad apart (the linear branch), q and -q (one rotation: no turn on the way),
  // and keys 180 degrees apart as rotations (dot 0: halfway is 90 degrees).
  const double e = 1e-10;
  const std::vector<std::array<double, 8>> cases = {
      {0, 0, std::sin(0.5), std::cos(0.5), 0, 0, std::sin(0.5 + e), std::cos(0.5 + e)},
      {0.1, 0.2, 0.3, 0.9, -0.1, -0.2, -0.3, -0.9},
      {0, 0, 0, 1, 1, 0, 0, 0}};
  for (const auto& k : cases) {
    const Track t = make_track(NodeProperty::rotation, Interpolation::linear, {0.0, 1.0},
                               std::vector<double>(k.begin(), k.end()));
    for (const double u : {0.0, 0.3, 0.5, 1.0}) {
      double out[4];
      sample(t, u, out);
      EXPECT_LT(rotation_distance(out, slerp_oracle({k[0], k[1], k[2], k[3]},
                                                    {k[4], k[5], k[6], k[7]}, u)),
                1e-15)
          << u;
    }
  }
}

TEST(Animation, CubicSplineReproducesTheCubicItsKeysAndTangentsCameFrom) {
  // p(t) = a + b t + c t^2 + d t^3 per component; keys p(t_k), tangents p'(t_k) per second.
  // The Hermite spline through them is p itself, whatever the key spacing.
  const double a[3] = {0.5, -2, 3}, b[3] = {1, 0.25, -4}, c[3] = {-0.5, 2, 0.125},
               d[3] = {0.25, -0.75, 1};
  const std::vector<double> times = {-1.0, -0.2, 0.05, 1.5, 4.0};
  std::vector<double> values;
  for (const double tk : times)
    for (int part = 0; part < 3; ++part)  // in-tangent, value, out-tangent
      for (int k = 0; k < 3; ++k)
        values.push_back(part == 1 ? a[k] + tk * (b[k] + tk * (c[k] + tk * d[k]))
                                   : b[k] + tk * (2 * c[k] + 3 * d[k] * tk));
  const Track t = make_track(NodeProperty::translation, Interpolation::cubic_spline, times, values);
  for (int i = 0; i <= 500; ++i) {
    const double s = -1.0 + 5.0 * i / 500.0;
    double out[3];
    sample(t, s, out);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(out[k], a[k] + s * (b[k] + s * (c[k] + s * d[k])), 1e-11) << s;
  }
}

TEST(Animation, BeforeTheFirstKeyAndAfterTheLastTheTrackHolds) {
  for (const Interpolation i : {Interpolation::step, Interpolation::linear, Interpolation::cubic_spline}) {
    const bool cubic = i == Interpolation::cubic_spline;
    std::vector<double> values;
    for (int key = 0; key < 2; ++key)
      for (int part = 0; part < (cubic ? 3 : 1); ++part)
        for (int k = 0; k < 3; ++k) values.push_back(!cubic || part == 1 ? 10.0 * key + k : 99.0);
    const Track t = make_track(NodeProperty::translation, i, {1.0, 2.0}, values);
    double out[3];
    sample(t, -1e30, out);
    EXPECT_EQ(out[1], 1.0);
    sample(t, 0.999, out);
    EXPECT_EQ(out[1], 1.0);
    sample(t, 2.0, out);
    EXPECT_EQ(out[1], 11.0);
    sample(t, 1e30, out);
    EXPECT_EQ(out[1], 11.0);
  }
}

TEST(Animation, WeightsInterpolateEachMorphTargetAndCubicSplinesKeepTheirWidth) {
  Track linear = make_track(NodeProperty::weights, Interpolation::linear, {0.0, 2.0},
                            {0.0, 1.0, 1.0, 0.0});
  double out[2];
  sample(linear, 0.5, out);
  EXPECT_EQ(out[0], 0.25);
  EXPECT_EQ(out[1], 0.75);
  // in-tangents, values, out-tangents of 2 weights per key; zero tangents: smoothstep
  Track cubic = make_track(NodeProperty::weights, Interpolation::cubic_spline, {0.0, 1.0},
                           {0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0});
  sample(cubic, 0.5, out);
  EXPECT_NEAR(out[0], 0.5, 1e-15);
  EXPECT_NEAR(out[1], 0.5, 1e-15);
  sample(cubic, 0.25, out);
  EXPECT_NEAR(out[0], 3 * 0.0625 - 2 * 0.015625, 1e-15);  // 3u^2 - 2u^3
  EXPECT_NEAR(out[1], 1 - out[0], 1e-15);
}

TEST(Animation, PoseMovesOnlyWhatItsChannelsTargetAndDurationIsTheLastKey) {
  Animation a;
  a.channels.push_back({1, make_track(NodeProperty::translation, Interpolation::linear,
                                      {0.0, 2.0}, {0, 0, 0, 2, 4, 6})});
  a.channels.push_back({0, make_track(NodeProperty::scale, Interpolation::step, {0.5, 3.5},
                                      {2, 2, 2, 3, 3, 3})});
  a.channels.push_back({7, make_track(NodeProperty::scale, Interpolation::step, {0.0}, {5, 5, 5})});
  EXPECT_EQ(a.duration(), 3.5);
  std::vector<NodeTrs> nodes(2);
  nodes[1].rotation = {0, 1, 0, 0};
  a.pose(1.0, nodes);  // node 7 does not exist: skipped
  EXPECT_EQ(nodes[1].translation, (std::array<double, 3>{1, 2, 3}));
  EXPECT_EQ(nodes[1].rotation, (std::array<double, 4>{0, 1, 0, 0}));
  EXPECT_EQ(nodes[1].scale, (std::array<double, 3>{1, 1, 1}));
  EXPECT_EQ(nodes[0].scale, (std::array<double, 3>{2, 2, 2}));
  EXPECT_EQ(nodes[0].translation, (std::array<double, 3>{0, 0, 0}));
}

TEST(Animation, MatrixOfTrsEqualsTranslateRotateByQuaternionSandwichScale) {
  std::mt19937 rng(3);
  std::normal_distribution<double> g;
  for (int i = 0; i < 200; ++i) {
    NodeTrs trs;
    trs.translation = {g(rng) * 10, g(rng) * 10, g(rng) * 10};
    trs.rotation = {g(rng), g(rng), g(rng), g(rng)};  // not unit: matrix_of normalizes
    trs.scale = {g(rng), g(rng), g(rng)};
    const Matrix4d m = matrix_of(trs);
    const Quat q = normalized({trs.rotation[0], trs.rotation[1], trs.rotation[2], trs.rotation[3]});
    const std::array<long double, 3> p = {g(rng), g(rng), g(rng)};
    const Quat scaled = {p[0] * trs.scale[0], p[1] * trs.scale[1], p[2] * trs.scale[2], 0};
    const Quat turned = multiply(multiply(q, scaled), conjugate(q));
    for (int r = 0; r < 3; ++r) {
      const long double got = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
      EXPECT_NEAR(double(got), double(turned[r] + trs.translation[r]), 1e-12 * 30) << i;
    }
    EXPECT_EQ(m[3], 0.0);
    EXPECT_EQ(m[7], 0.0);
    EXPECT_EQ(m[11], 0.0);
    EXPECT_EQ(m[15], 1.0);
  }
}

TEST(Animation, IdentityTrsGivesTheIdentityMatrixExactly) {
  EXPECT_EQ(matrix_of(NodeTrs{}), kIdentity4d);
}

}  // namespace
}  // namespace rt2
