// rt2/geometry/optics.h — the directions of reflected and refracted rays (thesis 3.2).
#pragma once

#include <cmath>

#include "rt2/geometry/ray.h"

namespace rt2 {

// R = I - 2 N (N·I) (thesis formula 1).
MLIB_INLINE vec4 reflect(const vec4& i, const vec4& n) { return i - 2.0f * n * dot(n, i); }

// T = eta I - (cos a + eta (N·I)) N with cos a = sqrt(1 - eta^2 (1 - (N·I)^2)), N facing
// the incoming ray (N·I < 0). Returns false on total internal reflection (negative root).
MLIB_INLINE bool refract(const vec4& i, const vec4& n, float eta, vec4& t) {
  const float n_dot_i = dot(n, i);
  const float k = 1.0f - eta * eta * (1.0f - n_dot_i * n_dot_i);
  if (k < 0.0f) return false;
  t = normalize(eta * i - (std::sqrt(k) + eta * n_dot_i) * n);
  return true;
}

}  // namespace rt2
