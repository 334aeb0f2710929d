// rt2/shading/sampling.h — deterministic sample points for the prefiltering of the environment
// (environment.cpp) and the tests' integrals: the Hammersley point set, GGX half vectors
// distributed as D(h) (n·h), and an orthonormal frame around a normal.
//
// Directions in a local frame have the normal along +z.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "rt2/geometry/ray.h"

namespace rt2 {

// Van der Corput's radical inverse in base 2: the bits of i mirrored about the binary
// point, in [0, 1).
inline float radical_inverse(std::uint32_t i) {
  i = (i << 16) | (i >> 16);
  i = ((i & 0x55555555u) << 1) | ((i & 0xAAAAAAAAu) >> 1);
  i = ((i & 0x33333333u) << 2) | ((i & 0xCCCCCCCCu) >> 2);
  i = ((i & 0x0F0F0F0Fu) << 4) | ((i & 0xF0F0F0F0u) >> 4);
  i = ((i & 0x00FF00FFu) << 8) | ((i & 0xFF00FF00u) >> 8);
  return float(i) * 0x1p-32f;
}

// The i-th of n Hammersley points in [0, 1)^2: (i / n, radical_inverse(i)), a
// low-discrepancy set (Pharr et al., PBRT 3rd ed. 7.4.1).
struct Point2 {
  float x, y;
};
inline Point2 hammersley(std::uint32_t i, std::uint32_t n) {
  return {float(i) / float(n), radical_inverse(i)};
}

// A half vector h (local frame, n = +z) with density D(h) (n·h) of GGX with `alpha`, from
// a point of [0, 1)^2 (Walter et al. 2007, eq. 35-36): cos^2 theta =
// (1 - u.y) / (1 + (alpha^2 - 1) u.y), phi = 2 pi u.x.
inline vec4 sample_ggx_half(Point2 u, float alpha) {
  const float a2 = alpha * alpha;
  const float cos2 = (1.0f - u.y) / (1.0f + (a2 - 1.0f) * u.y);
  const float cos_t = std::sqrt(cos2);
  const float sin_t = std::sqrt(std::max(0.0f, 1.0f - cos2));
  const float phi = 2.0f * std::numbers::pi_v<float> * u.x;
  return vec4(sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t);
}

// An orthonormal basis (t, b, n) around the unit vector n, without branches on the
// tangent's choice beyond a sign (Duff et al. 2017, "Building an Orthonormal Basis,
// Revisited"). to_world maps a local direction (normal along +z) into it.
struct Frame {
  vec4 t, b, n;
  explicit Frame(const vec4& normal) : n(normal) {
    const float nx = normal[0], ny = normal[1], nz = normal[2];
    const float sign = std::copysign(1.0f, nz);
    const float a = -1.0f / (sign + nz);
    const float c = nx * ny * a;
    t = vec4(1.0f + sign * nx * nx * a, sign * c, -sign * nx);
    b = vec4(c, sign + ny * ny * a, -ny);
  }
  vec4 to_world(const vec4& local) const { return t * local[0] + b * local[1] + n * local[2]; }
};

}  // namespace rt2
