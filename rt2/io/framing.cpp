// rt2/io/framing.cpp — a camera and a light around a bounding box (see rt2/io/framing.h).
#include "rt2/io/framing.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "rt2/base/error.h"
#include "rt2/io/scene_io.h"
#include "rt2/io/text.h"

namespace rt2::io {
namespace {

// The framed distance over the one at which the bounding sphere touches the image's edges.
constexpr float kFitMargin = 1.02f;

Framing framing(const Aabb& box) {
  Framing f;
  f.box = box;
  f.center = box.center();
  const vec4 half = box.extent() * 0.5f;
  f.radius = std::sqrt(float(dot(half, half)));  // half the diagonal
  return f;
}

}  // namespace

Framing framing_of(const std::string& file, const Aabb& box, const std::string& what) {
  const Framing f = framing(box);
  if (!(f.radius >= 1e-15f && f.radius <= 1e15f))
    error_at(file, 0, 0,
             "the " + what + " is too " + std::string(f.radius > 1.0f ? "large" : "small") +
                 " to frame (half diagonal " + fmt(f.radius) + ")");
  return f;
}

vec4 framing_direction(const Framing& f) {
  const vec4 e = f.box.extent();
  int axis[3] = {0, 1, 2};  // by extent, thinnest first
  std::sort(axis, axis + 3, [&](int a, int b) { return e[a] < e[b]; });
  const float middle = e[axis[1]];
  // 0 for a box whose two smaller extents are alike (a cube, a rod), 1 for a flat one.
  const float flatness = middle > 0.0f ? 1.0f - e[axis[0]] / middle : 0.0f;
  // Both ends have every component >= 1 / sqrt(6) = sin(24.09°), and so has any point
  // between them once normalised (its length is at most 1).
  const vec4 general = normalize(vec4(1.0f, 1.0f, 2.0f));
  vec4 flat(1.0f, 1.0f, 1.0f);
  flat[std::size_t(axis[0])] = 2.0f;
  return normalize(general * (1.0f - flatness) + normalize(flat) * flatness);
}

Camera framing_camera(const Framing& f, float aspect) {
  if (!(aspect > 0.0f && std::isfinite(aspect)))
    throw Error("framing: the image's aspect must be > 0, got " + fmt(aspect));
  const float half_v = 0.5f * kFramingFov * std::numbers::pi_v<float> / 180.0f;
  const float half_h = std::atan(aspect * std::tan(half_v));
  // A sphere of radius R lies inside an angle of half-width a seen from distance R / sin a.
  const float distance = kFitMargin * f.radius / std::sin(std::min(half_v, half_h));
  const vec4 d = framing_direction(f);
  const vec4 position = f.center + d * distance, forward = -d;
  return Camera(position, forward, vec4(0.0f, 1.0f, 0.0f), kFramingFov);
}

void frame_camera(Scene& scene, const Framing& f) {
  scene.camera = framing_camera(f, kFramingAspect);
  scene.framed_bounds = f.box;
}

Light framing_light(const Framing& f) {
  const vec4 d = framing_direction(f);
  const vec4 up(0.0f, 1.0f, 0.0f);
  const vec4 forward = -d;
  const vec4 right = normalize(cross(forward, up));
  Light light;
  light.position = f.center + (up * 3.0f + d * 2.0f + right) * f.radius;
  return light;
}

}  // namespace rt2::io

namespace rt2 {

// Declared in rt2/io/scene_io.h, the public face of framing.
void fit_framed_camera(Scene& scene, int width, int height) {
  if (!scene.framed_bounds) return;
  if (width <= 0 || height <= 0)
    throw Error("framing: the image must be at least 1 x 1, got " + std::to_string(width) +
                " x " + std::to_string(height));
  scene.camera =
      io::framing_camera(io::framing(*scene.framed_bounds), float(width) / float(height));
}

}  // namespace rt2
