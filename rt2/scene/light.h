// rt2/scene/light.h — point lights, with an optional finite range.
//
// A light without a range (range = +inf, the default) shines on every point it sees with
// its full radiance, as the thesis's lights do: Phong shading has no distance falloff. A
// light with a finite range is scaled by a window that is 1 at the light and falls smoothly
// to exactly 0 at `range` (zero derivative there: no visible edge; the window of Unreal
// Engine 4's and Frostbite's falloff, without the inverse square, which rt2's lights lack):
//   window(d) = (1 - (d / range)^4)^2  for d < range,  0 from range on
// Beyond its range a light can be skipped without changing a bit of the image
// (rt2/lights/light_bvh.h, the many-lights culling).
#pragma once

#include <cmath>

#include "rt2/geometry/ray.h"

namespace rt2 {

struct Light {
  vec4 position;                 // w = 0
  vec4 color{1.0f, 1.0f, 1.0f};  // linear RGB
  float intensity = 1.0f;
  float range = kInfinity;       // > 0; +inf: no range (no falloff)
  vec4 radiance() const { return color * intensity; }
  bool has_range() const { return range < kInfinity; }
};

// Whether a point at distance `distance` from `light` receives any of its light: the one
// test every light-culling mode is a superset of (the render kernel's shading applies it).
inline bool in_range(const Light& light, float distance) { return distance < light.range; }

// The falloff window at distance d < light.range of a light with a finite range.
inline float range_window(const Light& light, float distance) {
  const float x = distance / light.range;
  const float x2 = x * x;
  const float w = 1.0f - x2 * x2;
  return w * w;
}

}  // namespace rt2
