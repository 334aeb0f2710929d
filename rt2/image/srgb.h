// rt2/image/srgb.h — the sRGB transfer function (IEC 61966-2-1), for display image formats.
//
// Written here rather than taken from OpenImageIO's colorconvert: that one goes through
// OpenColorIO, whose meaning of "sRGB" follows the user's $OCIO configuration; rt2's files
// must not depend on the environment. Computed in double, so that encode(decode(x)) is
// exact for every 8-bit value.
#pragma once

#include <cmath>

namespace rt2 {

// Linear [0, 1] -> sRGB-encoded [0, 1]. Values outside are clamped first; NaN gives 0.
inline float srgb_encode(float linear) {
  if (!(linear > 0.0f)) return 0.0f;
  if (linear >= 1.0f) return 1.0f;
  const double x = linear;
  return static_cast<float>(x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055);
}

// sRGB-encoded [0, 1] -> linear [0, 1], the inverse of srgb_encode. Clamped like it.
inline float srgb_decode(float encoded) {
  if (!(encoded > 0.0f)) return 0.0f;
  if (encoded >= 1.0f) return 1.0f;
  const double x = encoded;
  return static_cast<float>(x <= 0.04045 ? x / 12.92 : std::pow((x + 0.055) / 1.055, 2.4));
}

}  // namespace rt2
