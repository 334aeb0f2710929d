// rt2/geometry/offset.h — where a secondary ray starts, so that it does not hit its own surface.
//
// Wächter and Binder, "A Fast and Robust Method for Avoiding Self-Intersection" (Ray
// Tracing Gems, ch. 6): the hit point is moved off the surface along the geometric normal
// by a fixed number of float ulps of each coordinate (so the offset scales with the
// magnitude of the point, from millimetre scenes to points 1e6 away), and by a small
// absolute amount near the origin where ulps vanish (scaled with the scene's size, below).
// The new ray then starts at t = 0. The hit point itself must be computed precisely
// (barycentric interpolation for triangles, re-projection for spheres and planes) for the
// offset to be sufficient.
#pragma once

#include "mlib/vfloat.h"
#include "rt2/geometry/ray.h"

namespace rt2 {

// One coordinate p of a point moved along the same coordinate n of the normal, lane by lane
// for any mlib::vfloat: by (int)(256 n) floats, or by scale / 65536 x n where |p| < scale /
// 32. The paper's constants assume a scene of size ~1: below |p| = 1/32 it offsets by the
// absolute 1/65536, which is 1.5 % of a millimetre-sized sphere. rt2 scales that region and
// that offset with the scene's size (`scale`, CompiledScene::offset_scale in
// rt2/render/compiled_scene.h), so scenes from millimetres to hundreds of kilometres get the
// same relative margin. The render kernel (rt2/kernel/) calls it on whole lanes of points.
template <class V>
MLIB_INLINE V offset_coordinate(V p, V n, float scale) {
  const V origin = V::broadcast(scale / 32.0f), float_scale = V::broadcast(scale / 65536.0f);
  return select(abs(p) < origin, p + float_scale * n, step_ulps(p, V::broadcast(256.0f) * n));
}

// p's x, y and z, each as offset_coordinate; w = 0.
MLIB_INLINE vec4 offset_ray_origin(const vec4& p, const vec4& n, float scale = 1.0f) {
  using mlib::vfloat4;
  const vfloat4 moved =
      offset_coordinate(vfloat4::from_f4(p.eval()), vfloat4::from_f4(n.eval()), scale);
  return mlib::simd::zero_w(moved.to_f4());
}

}  // namespace rt2
