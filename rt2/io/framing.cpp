// rt2/io/framing.cpp — a camera and a light around a bounding box (see rt2/io/framing.h).
#include "rt2/io/framing.h"

#include <cmath>
#include <string>

#include "rt2/io/text.h"

namespace rt2::io {

Framing framing_of(const std::string& file, const Aabb& box, const std::string& what) {
  Framing f;
  f.center = box.center();
  const vec4 half = box.extent() * 0.5f;
  f.radius = std::sqrt(float(dot(half, half)));  // half the diagonal
  if (!(f.radius >= 1e-15f && f.radius <= 1e15f))
    error_at(file, 0, 0,
             "the " + what + " is too " + std::string(f.radius > 1.0f ? "large" : "small") +
                 " to frame (half diagonal " + fmt(f.radius) + ")");
  return f;
}

Camera framing_camera(const Framing& f) {
  const float r = f.radius;
  return Camera::look_at(f.center + vec4(0.0f, 0.3f * r, 2.2f * r), f.center,
                         vec4(0.0f, 1.0f, 0.0f), 45.0f);
}

Light framing_light(const Framing& f) {
  const float r = f.radius;
  Light light;
  light.position = f.center + vec4(r, 3.0f * r, 2.0f * r);
  return light;
}

}  // namespace rt2::io
