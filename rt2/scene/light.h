// rt2/scene/light.h — point lights, with an optional finite range.
//
// A light without a range (range = +inf, the default) shines on every point it sees with
// its full radiance, as the thesis's lights do: Phong shading has no distance falloff. A
// light with a finite range is a real-time engine's "local" light: its radiance is scaled by
// a window that is 1 at the light, falls smoothly and reaches exactly 0 at `range`,
//   window(d) = (1 - (d / range)^4)^2  for d < range,  0 from range on
// (the window of the windowed inverse-square falloff that Unreal Engine 4 and Frostbite
// use, without the inverse square: rt2's lights have none, and a light whose range grows
// without bound tends to the light without one). Its derivative is 0 at d = range, so the
// lit region has no visible edge. Because the contribution is exactly 0 beyond the range,
// a light whose sphere of influence does not contain a point can be skipped there without
// changing a bit of the image (light_bvh.h, the many-lights culling).
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
// test every light-culling mode is a superset of (render: shade).
inline bool in_range(const Light& light, float distance) { return distance < light.range; }

// The falloff window at distance d < light.range of a light with a finite range.
inline float range_window(const Light& light, float distance) {
  const float x = distance / light.range;
  const float x2 = x * x;
  const float w = 1.0f - x2 * x2;
  return w * w;
}

}  // namespace rt2
