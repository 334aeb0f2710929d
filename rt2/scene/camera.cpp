// rt2/scene/camera.cpp — camera basis construction.
#include "rt2/scene/camera.h"

#include <cmath>
#include <numbers>

#include "rt2/base/error.h"

namespace rt2 {

Camera::Camera(const vec4& position, const vec4& direction, const vec4& up, float fov_degrees)
    : position_(position), fov_(fov_degrees) {
  if (!(fov_degrees > 0.0f && fov_degrees < 180.0f))
    throw Error("camera fov must be in (0, 180) degrees, got " + std::to_string(fov_degrees));
  forward_ = normalize(direction);
  right_ = normalize(cross(forward_, up));
  if (!(dot(right_, right_) > 0.5f))
    throw Error("camera up vector is zero or parallel to the view direction");
  up_ = cross(right_, forward_);
  tan_half_ = std::tan(0.5f * fov_degrees * std::numbers::pi_v<float> / 180.0f);
}

Camera Camera::look_at(const vec4& position, const vec4& target, const vec4& up,
                       float fov_degrees) {
  const vec4 d = target - position;
  if (!(dot(d, d) > 0.0f)) throw Error("camera target equals the camera position");
  return Camera(position, d, up, fov_degrees);
}

Camera Camera::from_file_values(const vec4& position, const vec4& direction, const vec4& up,
                                float fov_degrees) {
  return Camera(position, normalize(direction), normalize(up), fov_degrees);
}

}  // namespace rt2
