// rt2/shading/equirect.h — an equirectangular (latitude-longitude) map of RGB radiance over the
// sphere of directions, its direction <-> (u, v) convention and its bilinear lookup.
//
// Convention (the one of most HDR environment images): y is up.
//   u = 0.5 + atan2(d.x, -d.z) / (2 pi)   in [0, 1]: u = 0.5 looks along -z, u grows
//                                          towards +x (0.75 is +x, 0.25 is -x);
//   v = acos(d.y) / pi                    in [0, 1]: v = 0 is +y (the top row), 1 is -y.
// Texel (x, y) covers u in [x, x + 1) / width and v in [y, y + 1) / height: row 0 is the
// top. Lookups wrap around in u (u = 0 and u = 1 both look along +z) and clamp in v.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "rt2/geometry/ray.h"

namespace rt2 {

struct Uv {
  float u, v;
};

// atan2(y, x) and acos(x) by polynomials, cheaper than libm's for the lookups made per
// shaded point. Errors below 2e-6 and 1e-7 radians, a ten-thousandth of a texel of a
// 4096-wide map.
inline float fast_atan2(float y, float x) {
  constexpr float kPi = std::numbers::pi_v<float>;
  const float ax = std::fabs(x), ay = std::fabs(y);
  const float hi = std::max(ax, ay), lo = std::min(ax, ay);
  if (!(hi > 0.0f)) return 0.0f;  // (0, 0), as atan2(+0, +0)
  const float z = lo / hi, z2 = z * z;
  // minimax on [0, 1]
  float a = z * (0.99997726f + z2 * (-0.33262347f + z2 * (0.19354346f + z2 * (-0.11643287f +
                 z2 * (0.05265332f + z2 * -0.01172120f)))));
  if (ay > ax) a = 0.5f * kPi - a;
  if (x < 0.0f) a = kPi - a;
  return y < 0.0f ? -a : a;
}
inline float fast_acos(float x) {
  constexpr float kPi = std::numbers::pi_v<float>;
  const float ax = std::min(std::fabs(x), 1.0f);
  // Abramowitz and Stegun 4.4.46
  const float r = std::sqrt(1.0f - ax) *
                  (1.5707963050f + ax * (-0.2145988016f + ax * (0.0889789874f + ax * (-0.0501743046f +
                   ax * (0.0308918810f + ax * (-0.0170881256f + ax * (0.0066700901f +
                   ax * -0.0012624911f)))))));
  return x < 0.0f ? kPi - r : r;
}

// d unit length (y is clamped to [-1, 1], so a slightly longer d is fine).
inline Uv direction_to_uv(const vec4& d) {
  constexpr float kInvPi = std::numbers::inv_pi_v<float>;
  const float u = 0.5f + fast_atan2(d[0], -d[2]) * (0.5f * kInvPi);
  const float v = fast_acos(std::clamp(float(d[1]), -1.0f, 1.0f)) * kInvPi;
  return {u, v};
}

// The inverse: the unit direction at (u, v).
inline vec4 uv_to_direction(Uv uv) {
  constexpr float kPi = std::numbers::pi_v<float>;
  const float theta = uv.v * kPi;
  const float phi = (uv.u - 0.5f) * (2.0f * kPi);
  const float s = std::sin(theta);
  return vec4(s * std::sin(phi), std::cos(theta), -s * std::cos(phi));
}

// The solid angle of one texel of row y: (2 pi / width) (cos theta0 - cos theta1).
inline float texel_solid_angle(int y, int width, int height) {
  constexpr float kPi = std::numbers::pi_v<float>;
  const float t0 = kPi * float(y) / float(height);
  const float t1 = kPi * float(y + 1) / float(height);
  return 2.0f * kPi / float(width) * (std::cos(t0) - std::cos(t1));
}

// width x height texels of linear RGB radiance (w = 0), row-major, row 0 at the top.
struct EquirectMap {
  int width = 0;
  int height = 0;
  std::vector<vec4> texels;

  EquirectMap() = default;
  EquirectMap(int w, int h) : width(w), height(h), texels(std::size_t(w) * std::size_t(h)) {}

  vec4& at(int x, int y) { return texels[std::size_t(y) * std::size_t(width) + std::size_t(x)]; }
  const vec4& at(int x, int y) const {
    return texels[std::size_t(y) * std::size_t(width) + std::size_t(x)];
  }
  // The direction through the centre of texel (x, y).
  vec4 texel_direction(int x, int y) const {
    return uv_to_direction({(float(x) + 0.5f) / float(width), (float(y) + 0.5f) / float(height)});
  }

  // Bilinear between the four nearest texel centres, wrapping in u and clamping in v. Each
  // blend is a + (b - a) t, so a constant map returns its constant exactly. u may be any
  // finite value (it wraps); NaN gives texel 0's row and column.
  vec4 bilinear(Uv uv) const {
    const float x = uv.u * float(width) - 0.5f;
    float y = std::min(uv.v * float(height) - 0.5f, float(height - 1));
    if (!(y >= 0.0f)) y = 0.0f;  // also NaN
    const float fx = std::floor(x);
    const float fy = std::floor(y);
    const float tx = x - fx;
    const float ty = y - fy;
    const int x0 = wrap(fx);
    const int x1 = x0 + 1 == width ? 0 : x0 + 1;
    const int y0 = int(fy);
    const int y1 = std::min(y0 + 1, height - 1);
    const vec4 top = at(x0, y0) + (at(x1, y0) - at(x0, y0)) * tx;
    const vec4 bottom = at(x0, y1) + (at(x1, y1) - at(x0, y1)) * tx;
    return top + (bottom - top) * ty;
  }
  vec4 bilinear(const vec4& dir) const { return bilinear(direction_to_uv(dir)); }

 private:
  // floor(x) modulo width, in [0, width).
  int wrap(float fx) const {
    const float w = float(width);
    float m = fx - w * std::floor(fx / w);
    if (!(m >= 0.0f && m < w)) m = 0.0f;  // NaN, or rounding up to w
    return int(m);
  }
};

}  // namespace rt2
