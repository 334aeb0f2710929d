// rt2/scene/camera.h — the pinhole camera of thesis 3.3.
//
// Pixel (px, py) with 0 <= px < width, 0 <= py < height, continuous (a sample position
// inside the pixel; the pixel centre is px + 0.5):
//   x = 2 px / width - 1,  y = 1 - 2 py / height,
//   x *= aspect * tan(fov / 2),  y *= tan(fov / 2),  dir = normalize(Cd + Cr x + Cu y).
// `fov` is the FULL vertical angle of view (the thesis's `angle` is taken as the half
// angle, tan(angle) above); aspect = width / height. The thesis's Cl ("left") is named
// `right` here: image x grows to the right, so the vector it multiplies must point right
// (the thesis's world was left-handed). rt2 is right-handed: right = forward x up.
#pragma once

#include "rt2/geometry/ray.h"

namespace rt2 {

class Camera {
 public:
  Camera() : Camera(vec4(0, 0, 0), vec4(0, 0, -1), vec4(0, 1, 0), 60.0f) {}
  // From the thesis's vectors: position Cp, direction Cd, up Cu (made orthogonal to Cd).
  Camera(const vec4& position, const vec4& direction, const vec4& up, float fov_degrees);
  static Camera look_at(const vec4& position, const vec4& target, const vec4& up,
                        float fov_degrees);
  // The camera a scene file's [camera] table describes (scenes/FORMAT.md): `direction` (for
  // look_at: look_at - position) and `up` as written, normalised as the file reader does,
  // so that a camera printed with all its digits and read back is the same bits.
  static Camera from_file_values(const vec4& position, const vec4& direction, const vec4& up,
                                 float fov_degrees);

  // The primary ray through continuous pixel coordinates (px, py) of a width x height image.
  MLIB_INLINE Ray ray(float px, float py, int width, int height) const {
    return ray_at(image_x(px, width, height), image_y(py, height));
  }
  // Its steps, for rays that share a column or a row (the render kernel's packets): x and y
  // above, then the ray.
  MLIB_INLINE float image_x(float px, int width, int height) const {
    return (2.0f * px / float(width) - 1.0f) * (float(width) / float(height)) * tan_half_;
  }
  MLIB_INLINE float image_y(float py, int height) const {
    return (1.0f - 2.0f * py / float(height)) * tan_half_;
  }
  MLIB_INLINE Ray ray_at(float x, float y) const {
    return Ray(position_, normalize(forward_ + right_ * x + up_ * y));
  }

  // Moves the camera by `offset` (its orientation is kept).
  void translate(const vec4& offset) { position_ += offset; }

  const vec4& position() const { return position_; }
  const vec4& forward() const { return forward_; }
  const vec4& up() const { return up_; }
  const vec4& right() const { return right_; }
  float fov() const { return fov_; }

 private:
  vec4 position_, forward_, up_, right_;
  float fov_ = 60.0f;
  float tan_half_ = 0.577f;
};

}  // namespace rt2
