// rt2/scene/light_path.h — where `rt2cpr --animate-lights` moves a light: a fixed path per light,
// so that the light tree is rebuilt every frame over lights that really move.
//
// Light i goes round a horizontal circle through the position it was compiled at (its
// anchor), of radius range / 2 (a twentieth of the scene's size for a light without a
// range), one turn every 4 seconds, starting at the anchor at angle phase_i = 2 pi frac(i /
// golden ratio) on its circle (so that neighbours move apart). With the turn's cosine and
// sine computed once per frame (Turn), a light's position costs a few multiplications.
#pragma once

#include <cmath>
#include <cstddef>
#include <numbers>

#include "rt2/geometry/aabb.h"
#include "rt2/scene/light.h"

namespace rt2 {

struct LightPath {
  // Every path's turn after some seconds: cos(theta) - 1 (as -2 sin^2(theta / 2), exact
  // near 0) and sin(theta).
  struct Turn {
    float cos_minus_1 = 0.0f, sin = 0.0f;
  };
  static Turn turn(double seconds) {
    const double theta = 2.0 * std::numbers::pi * seconds / 4.0;
    const double half = std::sin(0.5 * theta);
    return {float(-2.0 * half * half), float(std::sin(theta))};
  }

  LightPath() = default;
  LightPath(const Light& light, std::size_t index, float scene_size)
      : anchor(light.position),
        radius(light.has_range() ? 0.5f * light.range : 0.05f * scene_size) {
    const double phase =
        2.0 * std::numbers::pi * std::fmod(double(index) * 0.6180339887498949, 1.0);
    cos_phase = float(std::cos(phase));
    sin_phase = float(std::sin(phase));
  }

  // anchor + radius (cos(phase + theta) - cos(phase), 0, sin(phase + theta) - sin(phase)).
  vec4 at(const Turn& t) const {
    return anchor + radius * vec4(cos_phase * t.cos_minus_1 - sin_phase * t.sin, 0.0f,
                                  sin_phase * t.cos_minus_1 + cos_phase * t.sin);
  }

  // A box holding the whole circle.
  Aabb bounds() const {
    const vec4 r(radius, 0.0f, radius);
    const vec4 c = anchor + radius * vec4(-cos_phase, 0.0f, -sin_phase);  // the centre
    Aabb b;
    b.grow(c - r);
    b.grow(c + r);
    return b;
  }

  vec4 anchor;
  float radius = 0.0f, cos_phase = 1.0f, sin_phase = 0.0f;
};

}  // namespace rt2
