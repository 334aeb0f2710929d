// Tone mapping (rt2/image/tonemap.h): each curve against its formula, exposure, the curve names,
// and write_image's split between display formats (tone-mapped, sRGB 8-bit) and float
// formats (linear, untouched).
#include "rt2/image/tonemap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "rt2/image/image_io.h"
#include "tests/rt2/temp_dir.h"

namespace rt2 {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// The values every curve is checked over: zero, tiny, around 1, large.
std::vector<float> sweep() {
  std::vector<float> v;
  for (float c = 0.0f; c <= 64.0f; c = c < 1e-3f ? c + 1e-4f : c * 1.05f + 1e-4f) v.push_back(c);
  return v;
}

double narkowicz(double c) {
  return c * (2.51 * c + 0.03) / (c * (2.43 * c + 0.59) + 0.14);
}

TEST(Tonemap, NoneIsTheIdentity) {
  const Display d{ToneCurve::none, 0.0f};
  EXPECT_TRUE(d.is_identity());
  for (const float c : sweep()) EXPECT_EQ(tonemap(c, d), c);
  EXPECT_EQ(tonemap(-0.5f, d), -0.5f);  // clamping is the encoding's job
  EXPECT_EQ(tonemap(7.0f, d), 7.0f);
}

TEST(Tonemap, ReinhardIsCOverOnePlusC) {
  const Display d{ToneCurve::reinhard, 0.0f};
  for (const float c : sweep()) EXPECT_NEAR(tonemap(c, d), c / (1.0 + c), 1e-6) << c;
  EXPECT_FLOAT_EQ(tonemap(1.0f, d), 0.5f);
}

TEST(Tonemap, AcesMatchesNarkowiczsFitAndIsClampedToTheUnitInterval) {
  const Display d{ToneCurve::aces, 0.0f};
  for (const float c : sweep()) {
    const float y = tonemap(c, d);
    EXPECT_NEAR(y, std::min(1.0, narkowicz(c)), 1e-5) << c;
    EXPECT_GE(y, 0.0f) << c;
    EXPECT_LE(y, 1.0f) << c;
  }
  EXPECT_GT(narkowicz(64.0), 1.0);  // the unclamped fit overshoots: the clamp is needed
  EXPECT_EQ(tonemap(64.0f, d), 1.0f);
}

TEST(Tonemap, EveryCurveIsMonotoneNonDecreasing) {
  for (const ToneCurve curve : {ToneCurve::none, ToneCurve::reinhard, ToneCurve::aces}) {
    const Display d{curve, 0.0f};
    float last = tonemap(0.0f, d);
    for (const float c : sweep()) {
      const float y = tonemap(c, d);
      EXPECT_GE(y, last) << tone_curve_name(curve) << " at " << c;
      last = y;
    }
  }
}

TEST(Tonemap, InfinityMapsToOneAndNanStaysNan) {
  for (const ToneCurve curve : {ToneCurve::reinhard, ToneCurve::aces}) {
    const Display d{curve, 0.0f};
    EXPECT_EQ(tonemap(kInf, d), 1.0f) << tone_curve_name(curve);
    EXPECT_TRUE(std::isnan(tonemap(std::nanf(""), d))) << tone_curve_name(curve);
    EXPECT_EQ(tonemap(-1.0f, d), 0.0f) << tone_curve_name(curve);
  }
}

TEST(Tonemap, ExposureOfOneStopDoublesBeforeTheCurve) {
  for (const ToneCurve curve : {ToneCurve::none, ToneCurve::reinhard, ToneCurve::aces}) {
    const Display plain{curve, 0.0f}, up{curve, 1.0f}, down{curve, -2.0f};
    for (const float c : {0.01f, 0.2f, 0.7f, 3.0f}) {
      EXPECT_FLOAT_EQ(tonemap(c, up), tonemap(2.0f * c, plain)) << tone_curve_name(curve);
      EXPECT_FLOAT_EQ(tonemap(c, down), tonemap(0.25f * c, plain)) << tone_curve_name(curve);
    }
  }
  EXPECT_FALSE((Display{ToneCurve::none, 1.0f}.is_identity()));
}

TEST(Tonemap, TheVectorFormMapsEveryValue) {
  std::vector<float> v{0.0f, 0.5f, 1.0f, 3.0f};
  tonemap(v, Display{ToneCurve::reinhard, 1.0f});
  EXPECT_FLOAT_EQ(v[0], 0.0f);
  EXPECT_FLOAT_EQ(v[1], 0.5f);
  EXPECT_FLOAT_EQ(v[2], 2.0f / 3.0f);
  EXPECT_FLOAT_EQ(v[3], 6.0f / 7.0f);
}

TEST(Tonemap, CurveNamesRoundTripAndAnUnknownNameIsRefused) {
  for (const ToneCurve curve : {ToneCurve::none, ToneCurve::reinhard, ToneCurve::aces}) {
    ToneCurve back = curve == ToneCurve::aces ? ToneCurve::none : ToneCurve::aces;
    ASSERT_TRUE(parse_tone_curve(tone_curve_name(curve), back)) << tone_curve_name(curve);
    EXPECT_EQ(back, curve);
  }
  EXPECT_STREQ(tone_curve_name(ToneCurve::reinhard), "reinhard");
  for (const char* bad : {"bogus", "", "ACES", "Reinhard", "none "}) {
    ToneCurve c = ToneCurve::reinhard;
    EXPECT_FALSE(parse_tone_curve(bad, c)) << bad;
    EXPECT_EQ(c, ToneCurve::reinhard) << "a refused name left the curve alone";
  }
}

// Values below, at and above 1, and 0.
Image hdr_ramp() {
  Image img(4, 2);
  const float values[] = {0.0f, 0.05f, 0.3f, 0.8f, 1.0f, 2.0f, 5.0f, 20.0f};
  for (std::size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = values[(i / 3 + i % 3) % 8];
  return img;
}

TEST(Tonemap, PngIsToneMappedAndExrKeepsTheLinearValues) {
  const test::TempDir tmp("tonemap_write");
  const Image img = hdr_ramp();
  const Display d{ToneCurve::reinhard, 0.0f};
  write_image(tmp.path("r.png"), img, d);
  write_image(tmp.path("r.exr"), img, d);
  const Image png = read_image(tmp.path("r.png"));
  const Image exr = read_image(tmp.path("r.exr"));
  ASSERT_EQ(png.rgb.size(), img.rgb.size());
  ASSERT_EQ(exr.rgb.size(), img.rgb.size());
  for (std::size_t i = 0; i < img.rgb.size(); ++i) {
    const float want = img.rgb[i] / (1.0f + img.rgb[i]);
    // 8-bit sRGB: half a step of the encoded value is at most ~1/255 linear near 1
    EXPECT_NEAR(png.rgb[i], want, 1.0f / 255.0f) << i;
    EXPECT_EQ(exr.rgb[i], img.rgb[i]) << i;
  }
}

// A NaN survives the curve (tonemap keeps it) and the 8-bit encoding writes it as 0.
TEST(Tonemap, NanIsWrittenAsBlackToADisplayFormat) {
  const test::TempDir tmp("tonemap_nan");
  Image img(2, 1);
  img.rgb = {std::nanf(""), 0.5f, kInf, 1.0f, std::nanf(""), 0.25f};
  for (const ToneCurve curve : {ToneCurve::none, ToneCurve::reinhard, ToneCurve::aces}) {
    const std::string path = tmp.path(std::string(tone_curve_name(curve)) + ".png");
    write_image(path, img, Display{curve, 0.5f});
    const Image back = read_image(path);
    ASSERT_EQ(back.rgb.size(), img.rgb.size());
    EXPECT_EQ(back.rgb[0], 0.0f) << tone_curve_name(curve);
    EXPECT_EQ(back.rgb[4], 0.0f) << tone_curve_name(curve);
    EXPECT_EQ(back.rgb[2], 1.0f) << tone_curve_name(curve);  // +inf: white
    EXPECT_GT(back.rgb[1], 0.0f) << tone_curve_name(curve);
  }
}

}  // namespace
}  // namespace rt2
