// The screen's pixels (display_pixels.h) against the exact curve: the table of the sRGB
// curve lands within one 8-bit step of srgb_encode after the same tone mapping, for values
// across and beyond [0, 1]; NaN and negatives are black, infinity and overflow white, alpha
// is opaque.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <random>

#include "rt2/image/display_pixels.h"
#include "rt2/image/srgb.h"

namespace rt2 {
namespace {

int exact(float v, const Display& d) {
  return int(std::lround(srgb_encode(tonemap(v, d)) * 255.0f));
}

TEST(DisplayPixels, WithinOneStepOfTheExactCurveForEveryToneCurve) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-0.1f, 1.5f);
  for (const Display d : {Display{}, Display{ToneCurve::reinhard, 0.0f},
                          Display{ToneCurve::aces, 1.5f}, Display{ToneCurve::none, -2.0f}}) {
    Image img(257, 64);
    for (std::size_t i = 0; i < img.rgb.size(); ++i)
      img.rgb[i] = i < 257 * 3 ? float(i) / float(257 * 3 - 1) : u(rng);  // a ramp, then random
    std::vector<std::uint8_t> px;
    to_display_pixels(img, d, px);
    ASSERT_EQ(px.size(), std::size_t(257 * 64 * 4));
    for (std::size_t p = 0; p < std::size_t(257 * 64); ++p) {
      for (std::size_t c = 0; c < 3; ++c)
        ASSERT_LE(std::abs(int(px[p * 4 + c]) - exact(img.rgb[p * 3 + c], d)), 1)
            << "value " << img.rgb[p * 3 + c] << " curve " << tone_curve_name(d.curve);
      ASSERT_EQ(px[p * 4 + 3], 255);
    }
  }
}

TEST(DisplayPixels, NanAndNegativeAreBlackInfinityAndOverflowWhite) {
  Image img(4, 1);
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  img.rgb = {nan, -1.0f, -inf, inf, 1e30f, 1.0f, 0.0f, -0.0f, 1e-30f, 0.5f, 0.5f, 0.5f};
  std::vector<std::uint8_t> px;
  to_display_pixels(img, Display{}, px);
  EXPECT_EQ(px[0], 0);
  EXPECT_EQ(px[1], 0);
  EXPECT_EQ(px[2], 0);
  EXPECT_EQ(px[4], 255);
  EXPECT_EQ(px[5], 255);
  EXPECT_EQ(px[6], 255);
  EXPECT_EQ(px[8], 0);
  EXPECT_EQ(px[9], 0);
  EXPECT_EQ(px[10], 0);
  EXPECT_EQ(px[12], exact(0.5f, Display{}));
}

}  // namespace
}  // namespace rt2
