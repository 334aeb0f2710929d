// rt2cpr/viewer/fly_camera.cpp — yaw and pitch about the scene's up axis, +y.
#include "rt2cpr/viewer/fly_camera.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace rt2cpr::viewer {

using rt2::vec4;

namespace {

constexpr double kMaxPitch = 89.0 * std::numbers::pi / 180.0;
constexpr double kRadiansPerPixel = 0.2 * std::numbers::pi / 180.0;
constexpr float kMaxCoordinate = 1e15f;

// The coordinate axis (signed) closest to v.
vec4 nearest_axis(const vec4& v) {
  const float a[3] = {v.x(), v.y(), v.z()};
  int best = 0;
  for (int i = 1; i < 3; ++i)
    if (std::fabs(a[i]) > std::fabs(a[best])) best = i;
  float u[3] = {0.0f, 0.0f, 0.0f};
  u[best] = a[best] < 0.0f ? -1.0f : 1.0f;
  return vec4(u[0], u[1], u[2]);
}

bool same_bits(const vec4& a, const vec4& b) {
  return a.x() == b.x() && a.y() == b.y() && a.z() == b.z();
}

// An `up` that, written into a scene file with the start camera's position and direction,
// gives the start camera bit for bit. A Camera keeps its up made orthogonal to the view, not
// the one it was given: most scenes give +y (or another axis); a rolled camera's own up
// gives the same view up to rounding.
vec4 file_up_of(const rt2::Camera& start) {
  for (const vec4& up : {vec4(0, 1, 0), nearest_axis(start.up())}) {
    if (!(std::fabs(float(dot(cross(start.forward(), up), cross(start.forward(), up)))) > 1e-8f)) continue;
    const rt2::Camera c = rt2::Camera::from_file_values(start.position(), start.forward(), up, start.fov());
    if (same_bits(c.forward(), start.forward()) && same_bits(c.up(), start.up()) &&
        same_bits(c.right(), start.right()))
      return up;
  }
  return start.up();
}

}  // namespace

FlyCamera::FlyCamera(const rt2::Camera& start, float speed)
    : position_(start.position()), up_(0.0f, 1.0f, 0.0f), view_up_(file_up_of(start)),
      direction_(start.forward()), fov_(start.fov()), speed_(speed) {
  const vec4 f = start.forward();
  // The heading: the view direction projected on the horizontal plane; looking straight up
  // or down, the camera's own up vector gives it.
  vec4 flat = f - up_ * float(dot(f, up_));
  if (!(float(dot(flat, flat)) > 1e-12f)) flat = start.up() - up_ * float(dot(start.up(), up_));
  north_ = normalize(flat);
  east_ = cross(north_, up_);
  pitch_ = std::clamp(std::asin(std::clamp(double(dot(f, up_)), -1.0, 1.0)), -kMaxPitch, kMaxPitch);
}

void FlyCamera::move(float forward, float right, float up, float seconds) {
  const vec4 f = direction_;
  // Right of the heading: never parallel to the up axis, whatever the pitch.
  const vec4 r = east_ * float(std::cos(yaw_)) - north_ * float(std::sin(yaw_));
  position_ += (f * forward + r * right + up_ * up) * (speed_ * seconds);
  // Where a scene file can put a camera (its numbers are at most 1e15), so that the
  // printed table always reads back.
  position_ = mlib::clamp(position_, vec4(-kMaxCoordinate, -kMaxCoordinate, -kMaxCoordinate),
                          vec4(kMaxCoordinate, kMaxCoordinate, kMaxCoordinate));
}

void FlyCamera::turn(float dx, float dy) {
  if (!std::isfinite(dx) || !std::isfinite(dy)) return;
  yaw_ = std::remainder(yaw_ + double(dx) * kRadiansPerPixel, 2.0 * std::numbers::pi);
  pitch_ = std::clamp(pitch_ - double(dy) * kRadiansPerPixel, -kMaxPitch, kMaxPitch);
  const double c = std::cos(pitch_);
  direction_ = north_ * float(c * std::cos(yaw_)) + east_ * float(c * std::sin(yaw_)) +
               up_ * float(std::sin(pitch_));
  view_up_ = up_;  // first person from now on: no roll
}

void FlyCamera::scale_speed(float steps) {
  if (!std::isfinite(steps)) return;
  speed_ = std::clamp(speed_ * std::pow(1.25f, steps), 1e-6f, 1e9f);
}

rt2::Camera FlyCamera::camera() const {
  return rt2::Camera::from_file_values(position_, direction_, view_up_, fov_);
}

std::string FlyCamera::toml() const {
  const auto v = [](const vec4& a) {
    char b[128];
    std::snprintf(b, sizeof b, "[%.9g, %.9g, %.9g]", double(a.x()), double(a.y()), double(a.z()));
    return std::string(b);
  };
  char fov[32];
  std::snprintf(fov, sizeof fov, "%.9g", double(fov_));
  return "[camera]\nposition = " + v(position_) + "\ndirection = " + v(direction_) +
         "\nup = " + v(view_up_) + "\nfov = " + fov + "\n";
}

}  // namespace rt2cpr::viewer
