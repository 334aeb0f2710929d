// rt2/material.h — Phong materials (thesis 3.2).
#pragma once

#include <cstdint>
#include <string>

#include "rt2/ray.h"

namespace rt2 {

// I_local = Ka I_amb + sum over visible lights [Kd I (L·N) + Ks I (R·V)^n];
// I = I_local + Kr I_reflected + Kt I_refracted. Colours are linear RGB in lanes x y z.
struct Material {
  vec4 ambient{0.1f, 0.1f, 0.1f};   // Ka
  vec4 diffuse{0.7f, 0.7f, 0.7f};   // Kd
  vec4 specular{0.0f, 0.0f, 0.0f};  // Ks
  float shininess = 32.0f;          // Phong exponent n (>= 0)
  float reflectivity = 0.0f;        // Kr in [0, 1]
  float transparency = 0.0f;        // Kt in [0, 1]; also how much light passes in shadows
  float ior = 1.5f;                 // refractive index (> 0), used when Kt > 0
  // Optional 3D checker: where floor(x/s) + floor(y/s) + floor(z/s) is odd, Kd is
  // replaced by `diffuse2`. Off when checker_scale is 0.
  vec4 diffuse2{0.1f, 0.1f, 0.1f};
  float checker_scale = 0.0f;

  bool has_specular() const { return specular[0] > 0 || specular[1] > 0 || specular[2] > 0; }
  // Kd at the world-space point p: `diffuse`, or `diffuse2` on the checker's odd cells.
  vec4 diffuse_at(const vec4& p) const;
};

}  // namespace rt2
