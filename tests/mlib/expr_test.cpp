// Expression templates: the shape of an expression (a tree of nodes, not a vec4), its
// scalar-ness, and that evaluating the tree once equals eager step-by-step evaluation.
#include <gtest/gtest.h>

#include <type_traits>

#include "mlib/vec4_functions.h"
#include "tests/mlib/reference.h"

namespace mlib::test {
namespace {

TEST(Expr, ArithmeticBuildsATreeNotAVec4) {
  vec4 a, b, c;
  using Sum = decltype(a + b);
  static_assert(std::is_same_v<Sum, Binary<ops::Add, vec4, vec4>>);
  using Tree = decltype(a + b * c);
  static_assert(std::is_same_v<Tree, Binary<ops::Add, vec4, Binary<ops::Mul, vec4, vec4>>>);
  using Scaled = decltype(2.0f * a);
  static_assert(std::is_same_v<Scaled, Binary<ops::Mul, ScalarLeaf, vec4>>);
  using Reflect = decltype(a - 2.0f * b * dot(b, a));
  static_assert(std::is_same_v<
                Reflect,
                Binary<ops::Sub, vec4,
                       Binary<ops::Mul, Binary<ops::Mul, ScalarLeaf, vec4>,
                              Binary<ops::Dot, vec4, vec4>>>>);
  static_assert(!std::is_same_v<decltype(normalize(a - b)), vec4>);
  SUCCEED();
}

TEST(Expr, NodesHoldOnlyTheirLeaves) {
  vec4 a, b;
  // A node is the sum of its leaves: 16 bytes per vec4 or broadcast scalar, nothing else.
  static_assert(sizeof(decltype(a + b)) == 32);
  static_assert(sizeof(decltype(a - 2.0f * b * dot(b, a))) == 5 * 16);  // a, 2, b, b, a
  static_assert(sizeof(decltype(normalize(a))) == 16);
  SUCCEED();
}

TEST(Expr, ScalarnessPropagatesThroughLanewiseOpsOnly) {
  vec4 a, b;
  static_assert(decltype(dot(a, b))::scalar);
  static_assert(decltype(2.0f * dot(a, b) + 1.0f)::scalar);
  static_assert(decltype(dot(a + b, a - b))::scalar);
  static_assert(!decltype(a * dot(a, b))::scalar);
  static_assert(!decltype(cross(a, b))::scalar);
  static_assert(!decltype(normalize(dot(a, b) * a))::scalar);
  static_assert(std::is_convertible_v<decltype(dot(a, b) * 3.0f), float>);
  static_assert(!std::is_convertible_v<decltype(a + b), float>);
  SUCCEED();
}

TEST(Expr, ScalarExpressionConvertsToFloatAndMixesWithNumbers) {
  const vec4 a(1, 2, 3, 0), b(4, 5, 6, 0);
  const float d = dot(a, b);
  EXPECT_EQ(d, 32.0f);
  const float e = dot(a, b) * 0.5f + 1.0f;
  EXPECT_EQ(e, 17.0f);
  const float f = 1.0f / dot(a, a);
  EXPECT_FLOAT_EQ(f, 1.0f / 14.0f);
  EXPECT_FLOAT_EQ(std::sqrt(float(dot(a, a))), std::sqrt(14.0f));
}

TEST(Expr, SingleTreeEqualsEagerStepByStepEvaluation) {
  const auto as = random_refs(500, 40), bs = random_refs(500, 41), cs = random_refs(500, 42),
             ds = random_refs(500, 43), es = random_refs(500, 44);
  for (std::size_t k = 0; k < as.size(); ++k) {
    const vec4 a = make(as[k]), b = make(bs[k]), c = make(cs[k]), d = make(ds[k]),
               e = make(es[k]);
    const vec4 lazy = a + b * dot(c, d) - 0.5f * e;
    // Eager: every intermediate materialised as a vec4.
    const vec4 t1 = dot(c, d);
    const vec4 t2 = b * t1;
    const vec4 t3 = a + t2;
    const vec4 t4 = vec4(0.5f) * e;
    const vec4 eager = t3 - t4;
    for (int i = 0; i < 4; ++i) ASSERT_TRUE(same_bits(lazy[i], eager[i])) << k;
  }
}

TEST(Expr, FreeFunctionsAcceptExpressions) {
  const vec4 a(1.0f), b(3.0f);
  const vec4 lazy = normalize(b - a * dot(a + b, b));  // the thesis's example
  const vec4 s = a + b;
  const vec4 inner = b - a * vec4(dot(s, b));
  const vec4 eager = normalize(inner);
  EXPECT_EQ(ref(lazy), ref(eager));
  EXPECT_EQ(ref(vec4(abs(a - b))), ref(vec4(2.0f)));
  EXPECT_EQ(ref(vec4(cross(a + a, b - a))), ref(vec4(0.0f)));  // parallel
  EXPECT_EQ(calc_distance(a + b, b), 1.0f * 2.0f);  // |(1,1,1,1)| = 2
  EXPECT_EQ(to_color(a * 0.0f + 1.0f), 0xFFFFFFu);
  EXPECT_EQ(ref(vec4(clamp(a - b, -1.0f, b))), ref(vec4(-1.0f)));
}

TEST(Expr, OperandsAreCapturedByValueWhenTheExpressionIsBuilt) {
  vec4 a(1.0f), b(2.0f);
  const auto e = a + b;  // holds copies: can never dangle
  a = vec4(100.0f);
  EXPECT_EQ(vec4(e), vec4(3.0f));
}

TEST(Expr, ReflectFormulaMatchesScalarReflection) {
  const auto ns = random_refs(500, 45), is = random_refs(500, 46);
  for (std::size_t k = 0; k < ns.size(); ++k) {
    const vec4 n = normalize(make(ns[k])), i = make(is[k]);
    const vec4 r = i - 2.0f * n * dot(n, i);
    const double nd = dot_ref(ref(n), ref(i));
    for (int l = 0; l < 4; ++l)
      ASSERT_NEAR(r[l], i[l] - 2.0 * n[l] * nd,
                  1e-6 * (std::fabs(i[l]) + 2 * std::fabs(nd)) + 1e-30)
          << k;
  }
}

}  // namespace
}  // namespace mlib::test
