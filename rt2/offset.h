// rt2/offset.h — where a secondary ray starts, so that it does not hit its own surface.
//
// Wächter and Binder, "A Fast and Robust Method for Avoiding Self-Intersection" (Ray
// Tracing Gems, ch. 6): the hit point is moved off the surface along the geometric normal
// by a fixed number of float ulps of each coordinate (so the offset scales with the
// magnitude of the point, from millimetre scenes to points 1e6 away), and by a small
// absolute amount near the origin where ulps vanish. The new ray then starts at t = 0.
// The hit point itself must be computed precisely (barycentric interpolation for
// triangles, re-projection for spheres and planes) for the offset to be sufficient.
//
// The paper's constants assume a scene of size ~1: below |p| = 1/32 it offsets by the
// absolute 1/65536, which is 1.5 % of a millimetre-sized sphere. rt2 scales that region
// and that offset with the scene's size (`scale`, Renderer::offset_scale()), so scenes from
// millimetres to hundreds of kilometres get the same relative margin.
#pragma once

#include "rt2/ray.h"

namespace rt2 {

MLIB_INLINE vec4 offset_ray_origin(const vec4& p, const vec4& n, float scale = 1.0f) {
  const float origin = scale / 32.0f;
  const float float_scale = scale / 65536.0f;
  constexpr float kIntScale = 256.0f;
  // Per lane: p moved by (int)(256 n) floats, or by float_scale n where |p| < origin; w = 0.
  namespace simd = mlib::simd;
  const vec4 moved = simd::step_ulps(p.eval(), (kIntScale * n).eval());
  const vec4 near = p + float_scale * n;
  const simd::f4 is_near = simd::cmp_lt(simd::abs(p.eval()), simd::set1(origin));
  return simd::zero_w(simd::blend(is_near, moved.eval(), near.eval()));
}

}  // namespace rt2
