// Subpixel patterns: counts, positions inside the pixel, and the properties each claims.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "rt2/base/error.h"
#include "rt2/render/supersampling.h"

namespace rt2 {
namespace {

TEST(Supersampling, BothPatternsGiveExactlyNSamplesInsideThePixel) {
  for (Pattern p : {Pattern::grid, Pattern::circle})
    for (int n = 1; n <= 64; ++n) {
      const auto offs = subpixel_offsets(n, p);
      ASSERT_EQ(offs.size(), std::size_t(n)) << pattern_name(p);
      for (const auto& o : offs) {
        EXPECT_GT(o.x, 0.0f);
        EXPECT_LT(o.x, 1.0f);
        EXPECT_GT(o.y, 0.0f);
        EXPECT_LT(o.y, 1.0f);
      }
    }
}

TEST(Supersampling, OneSampleIsThePixelCentre) {
  for (Pattern p : {Pattern::grid, Pattern::circle}) {
    const auto offs = subpixel_offsets(1, p);
    EXPECT_EQ(offs[0].x, 0.5f);
    EXPECT_EQ(offs[0].y, 0.5f);
  }
}

TEST(Supersampling, GridOfASquareNumberIsTheUniformGrid) {
  const auto offs = subpixel_offsets(9, Pattern::grid);
  std::set<float> xs, ys;
  for (const auto& o : offs) {
    xs.insert(o.x);
    ys.insert(o.y);
  }
  EXPECT_EQ(xs, (std::set<float>{1 / 6.0f, 0.5f, 5 / 6.0f}));
  EXPECT_EQ(ys, (std::set<float>{1 / 6.0f, 0.5f, 5 / 6.0f}));
}

TEST(Supersampling, SamplesAreCentredOnThePixelCentre) {
  for (Pattern p : {Pattern::grid, Pattern::circle})
    for (int n : {2, 3, 4, 5, 8, 9, 16, 18}) {
      double sx = 0, sy = 0;
      for (const auto& o : subpixel_offsets(n, p)) {
        sx += o.x;
        sy += o.y;
      }
      EXPECT_NEAR(sx / n, 0.5, 1e-6) << pattern_name(p) << " " << n;
      EXPECT_NEAR(sy / n, 0.5, 1e-6) << pattern_name(p) << " " << n;
    }
}

TEST(Supersampling, CircleSamplesHaveDistinctXsAndDistinctYs) {
  // The thesis's claim rests on this: an axis-aligned edge sees N + 1 coverage levels.
  for (int n = 2; n <= 64; ++n) {
    const auto offs = subpixel_offsets(n, Pattern::circle);
    std::vector<float> xs, ys;
    for (const auto& o : offs) {
      xs.push_back(o.x);
      ys.push_back(o.y);
    }
    std::sort(xs.begin(), xs.end());
    std::sort(ys.begin(), ys.end());
    for (int i = 1; i < n; ++i) {
      EXPECT_GT(xs[i] - xs[i - 1], 1e-5f) << n;
      EXPECT_GT(ys[i] - ys[i - 1], 1e-5f) << n;
    }
  }
}

TEST(Supersampling, CircleRadiusMatchesUniformSpread) {
  for (const auto& o : subpixel_offsets(12, Pattern::circle))
    EXPECT_NEAR(std::hypot(o.x - 0.5f, o.y - 0.5f), std::sqrt(1.0f / 6.0f), 1e-6f);
}

TEST(Supersampling, RejectsZeroAndNegativeCountsAndUnknownPatterns) {
  EXPECT_THROW(subpixel_offsets(0, Pattern::grid), Error);
  EXPECT_THROW(subpixel_offsets(-3, Pattern::circle), Error);
  EXPECT_THROW(parse_pattern("hexagon"), Error);
  EXPECT_EQ(parse_pattern("circle"), Pattern::circle);
}

}  // namespace
}  // namespace rt2
