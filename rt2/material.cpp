// rt2/material.cpp — the checker texture.
#include "rt2/material.h"

#include <cmath>

namespace rt2 {

vec4 Material::diffuse_at(const vec4& p) const {
  if (!(checker_scale > 0.0f)) return diffuse;
  const float inv = 1.0f / checker_scale;
  const auto cell = [&](int a) { return static_cast<long long>(std::floor(p[a] * inv)); };
  return ((cell(0) + cell(1) + cell(2)) & 1) ? diffuse2 : diffuse;
}

}  // namespace rt2
