// The film (rt2/image/film.h) against a plain compensated sum kept here: a pixel's mean is
// the same bits whatever the film's memory held before it was cleared, with the first
// sample added without reading the sums and the second taking the compensation the first
// one left (signed zeros, tiny and huge values among the samples; a pixel that meets NaN or
// an infinity resolves to black and is counted either way); samples added together as one
// by one.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "rt2/image/film.h"

namespace rt2 {
namespace {

// Kahan's summation from zeros, step by step, with the compensation always stored.
struct KahanPixel {
  vec4 sum, carry;
  std::uint32_t n = 0;
  void add(const vec4& c) {
    const vec4 y = c - carry;
    const vec4 t = sum + y;
    carry = (t - sum) - y;
    sum = t;
    ++n;
  }
  // Film::resolve's mean: black without samples or where not finite.
  void mean(float* rgb) const {
    vec4 m;
    if (n > 0) m = sum / float(n);
    if (!(std::isfinite(m[0]) && std::isfinite(m[1]) && std::isfinite(m[2]))) m = vec4();
    for (int c = 0; c < 3; ++c) rgb[c] = m[c];
  }
};

// The sample value k of pixel i: large and small magnitudes (where the compensation
// carries), signed zeros, infinities and NaN.
vec4 sample(int i, int k) {
  constexpr float inf = std::numeric_limits<float>::infinity();
  const float values[] = {1e8f, 1.0f, -0.0f, 3.0e-39f, 0.1f, -7.5f, 1e30f, -1e30f, 0.3f, inf,
                          std::numeric_limits<float>::quiet_NaN(), 2.5e-8f};
  const auto v = [&](int j) { return values[(i * 7 + k * 5 + j * 3) % 12]; };
  // most pixels avoid the non-finite values, so that their means show the sums' bits
  if (i % 5 != 0)
    return vec4((i % 3 ? 1e8f : 1.0f) + float(k), 1.0f / float(k + 1), -0.0f);
  return vec4(v(0), v(1), v(2));
}

bool same_bits(const float* a, const float* b, int n) {
  return std::memcmp(a, b, sizeof(float) * std::size_t(n)) == 0;
}

TEST(Film, MeansMatchAPlainCompensatedSumAfterAClearWhateverTheMemoryHeld) {
  constexpr int w = 7, h = 5;
  Film film(w, h);
  // garbage first: every pixel given samples that leave large sums and compensations
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < 3; ++k) film.add(x, y, vec4(1e20f, -3.0f, 7.0f) * float(k + x + 1));
  film.clear();
  for (int passes : {1, 2, 5}) {
    std::vector<KahanPixel> ref(std::size_t(w * h));
    for (int k = 0; k < passes; ++k)
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const int i = y * w + x;
          film.add(x, y, sample(i, k));
          ref[std::size_t(i)].add(sample(i, k));
        }
    Image image;
    std::uint64_t nonfinite = film.resolve(image);
    std::vector<float> expected(std::size_t(w * h * 3));
    std::uint64_t expected_nonfinite = 0;
    for (int i = 0; i < w * h; ++i) {
      ref[std::size_t(i)].mean(&expected[std::size_t(i) * 3]);
      vec4 m = ref[std::size_t(i)].sum / float(ref[std::size_t(i)].n);
      expected_nonfinite += !(std::isfinite(m[0]) && std::isfinite(m[1]) && std::isfinite(m[2]));
    }
    EXPECT_TRUE(same_bits(image.rgb.data(), expected.data(), w * h * 3)) << passes << " passes";
    EXPECT_EQ(nonfinite, expected_nonfinite) << passes << " passes";
    EXPECT_GT(expected_nonfinite, 0u);  // the edges are reached
    EXPECT_EQ(film.samples(w - 1, h - 1), std::uint32_t(passes));
    film.clear();
  }
}

TEST(Film, ClearingATileDropsItsSamplesOnlyAndItsPixelsStartFromZero) {
  Film film(6, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 6; ++x) film.add(x, y, vec4(1e8f, float(x), float(y)));
  film.clear(Tile{2, 1, 5, 3});
  KahanPixel fresh, kept;
  kept.add(vec4(1e8f, 0.0f, 0.0f));
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 6; ++x) film.add(x, y, vec4(1.0f, 0.25f, -0.0f));
  fresh.add(vec4(1.0f, 0.25f, -0.0f));
  kept.add(vec4(1.0f, 0.25f, -0.0f));
  Image image;
  EXPECT_EQ(film.resolve(image), 0u);
  float a[3], b[3];
  fresh.mean(a);
  kept.mean(b);
  EXPECT_EQ(film.samples(3, 2), 1u);
  EXPECT_EQ(film.samples(0, 0), 2u);
  EXPECT_TRUE(same_bits(&image.rgb[std::size_t(2 * 6 + 3) * 3], a, 3));  // cleared
  EXPECT_TRUE(same_bits(&image.rgb[0], b, 3));                            // kept
}

TEST(Film, SamplesAddedTogetherEqualSamplesAddedOneByOneInEveryPass) {
  constexpr int w = 5, h = 4;
  Film one(w, h), together(w, h);
  for (int count : {1, 3, 2, 4}) {  // passes of 1, 3, 2 and 4 samples per pixel
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        std::vector<vec4> colors;
        for (int k = 0; k < count; ++k) colors.push_back(sample(y * w + x, k + count));
        for (const vec4& c : colors) one.add(x, y, c);
        together.add(x, y, colors.data(), count);
      }
    Image a, b;
    EXPECT_EQ(one.resolve(a), together.resolve(b)) << count;
    EXPECT_TRUE(same_bits(a.rgb.data(), b.rgb.data(), w * h * 3)) << count;
    EXPECT_EQ(one.samples(w - 1, h - 1), together.samples(w - 1, h - 1));
  }
}

}  // namespace
}  // namespace rt2
