// rt2/image/display_pixels.cpp — exposure, tone curve and a table of the sRGB curve.
#include "rt2/image/display_pixels.h"

#include <array>
#include <cmath>

#include "rt2/image/srgb.h"

namespace rt2 {

namespace {

constexpr int kSteps = 4096;

// The 8-bit sRGB value of linear i / (kSteps - 1).
const std::array<std::uint8_t, kSteps>& srgb_table() {
  static const std::array<std::uint8_t, kSteps> table = [] {
    std::array<std::uint8_t, kSteps> t{};
    for (int i = 0; i < kSteps; ++i)
      t[std::size_t(i)] = std::uint8_t(std::lround(srgb_encode(float(i) / float(kSteps - 1)) * 255.0f));
    return t;
  }();
  return table;
}

}  // namespace

void to_display_pixels(const Image& image, const Display& display, std::vector<std::uint8_t>& rgba) {
  const auto& table = srgb_table();
  const bool identity = display.is_identity();
  const std::size_t n = std::size_t(image.width) * std::size_t(image.height);
  rgba.resize(n * 4);
  for (std::size_t p = 0; p < n; ++p) {
    for (std::size_t c = 0; c < 3; ++c) {
      float v = image.rgb[p * 3 + c];
      if (!identity) v = tonemap(v, display);
      // NaN and values <= 0 are black, values >= 1 white (as srgb_encode clamps).
      const int i = v > 0.0f ? (v < 1.0f ? int(v * float(kSteps - 1) + 0.5f) : kSteps - 1) : 0;
      rgba[p * 4 + c] = table[std::size_t(i)];
    }
    rgba[p * 4 + 3] = 255;
  }
}

}  // namespace rt2
