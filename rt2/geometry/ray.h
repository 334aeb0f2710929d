// rt2/geometry/ray.h — a ray, its precomputed reciprocal direction, and the hit record.
//
// Invariant: `dir` is unit length (the camera normalises, reflection and refraction keep
// it), and every vec4 that is a point or a direction has w = 0. A ray covers the open
// parametric interval (t_min, t_max); t is a distance along `dir`.
#pragma once

#include <cstdint>
#include <limits>

#include "mlib/vec4_functions.h"

namespace rt2 {

using mlib::vec4;

inline constexpr float kInfinity = std::numeric_limits<float>::infinity();

enum class RayKind : std::uint8_t { primary, shadow, reflection, refraction };

struct Ray {
  vec4 org;
  vec4 dir;  // unit length, w = 0

  Ray() = default;
  Ray(const vec4& o, const vec4& d) : org(o), dir(d) {}
  vec4 at(float t) const { return org + dir * t; }
};

// Rays as structure of arrays (a batch's columns): component a (x, y, z, w) of ray i's
// origin at org[a][i], of its direction at dir[a][i].
struct RayColumns {
  const float* org[4];
  const float* dir[4];
};

// The traversal form: origin, direction and 1/direction (IEEE: ±inf for a zero component,
// which the slab test handles, see aabb.h). Lane w of inv_dir is 0 so that w lanes of box
// arithmetic stay 0 rather than 0 * inf.
struct RayPre {
  vec4 org;
  vec4 dir;
  vec4 inv_dir;
  RayPre() = default;
  explicit RayPre(const Ray& r)
      : org(r.org), dir(r.dir),
        inv_dir(mlib::simd::zero_w(vec4(vec4(1.0f, 1.0f, 1.0f, 0.0f) / r.dir).m128())) {}
};

// Which primitive was hit. A primitive reference packs its kind into the top two bits.
using PrimRef = std::uint32_t;
inline constexpr PrimRef kTriangleTag = 0u << 30;
inline constexpr PrimRef kSphereTag = 1u << 30;
inline constexpr PrimRef kPlaneTag = 2u << 30;
inline constexpr PrimRef kTagMask = 3u << 30;
inline constexpr PrimRef kNoHit = ~0u;

inline constexpr PrimRef prim_tag(PrimRef r) { return r & kTagMask; }
inline constexpr std::uint32_t prim_index(PrimRef r) { return r & ~kTagMask; }

// Not in an instance (a hit on the world's own geometry).
inline constexpr std::uint32_t kNoInstance = ~0u;

struct Hit {
  float t = kInfinity;
  float u = 0.0f, v = 0.0f;  // barycentrics of a triangle hit
  PrimRef prim = kNoHit;
  std::uint32_t instance = kNoInstance;  // Accel::instances, for a triangle in one
  bool found() const { return prim != kNoHit; }
};

}  // namespace rt2
