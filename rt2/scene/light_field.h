// rt2/scene/light_field.h — many lights scattered at random in a box, for many-light scenes.
//
// A scene's [light_field] (scenes/FORMAT.md) asks for `count` point lights placed uniformly
// at random in a box, each with a range drawn uniformly from [range_lo, range_hi] (the
// clustered-lighting text's scenes: radius 0.3, or 1 to 2 units, in Sponza). Light k of a
// field depends only on the seed and k (a hash, not a running generator), so asking for more
// lights (rt2cpr --lights) keeps the first ones where they were.
#pragma once

#include <cstddef>
#include <cstdint>

#include "rt2/geometry/aabb.h"
#include "rt2/scene/light.h"

namespace rt2 {

struct LightField {
  Aabb box;                             // where the lights are
  float range_lo = 1.0f, range_hi = 1.0f;  // each light's range, uniform in [lo, hi]
  vec4 color{1.0f, 1.0f, 1.0f};
  float intensity = 1.0f;
  std::uint64_t seed = 1;
  std::size_t first = 0;  // Scene::lights index of the field's light 0

  // The field's light k.
  Light light(std::size_t k) const {
    std::uint64_t state = seed * 0x9E3779B97F4A7C15ull + k;
    const auto uniform = [&state]() {  // splitmix64, top 24 bits: a float in [0, 1)
      std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
      z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
      z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
      z ^= z >> 31;
      return float(z >> 40) * 0x1p-24f;
    };
    Light l;
    const float x = uniform(), y = uniform(), z = uniform(), r = uniform();
    l.position = box.lo + vec4(x, y, z) * box.extent();
    l.range = range_lo + r * (range_hi - range_lo);
    l.color = color;
    l.intensity = intensity;
    return l;
  }
};

}  // namespace rt2
