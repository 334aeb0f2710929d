// rt2/kernel/secondary_rays.h — the secondary rays a material model spawns into the next
// batch: reflected rays, and transmitted rays refracted (Snell, geometry/optics.h) or
// reflected on total internal reflection; a ray whose weight does not pass min_weight is
// not traced.
#pragma once

#include "rt2/kernel/kernel.h"

#include "rt2/geometry/offset.h"
#include "rt2/geometry/optics.h"
#include "rt2/kernel/batches.h"
#include "rt2/render/compiled_scene.h"
#include "rt2/render/ray_counts.h"

namespace rt2::RT2_ISA {

// Appends a child of `parent` to the next batch, and counts it by kind.
MLIB_INLINE void push_path_ray(Batches& b, const vec4& org, const vec4& dir, const vec4& weight,
                               const PathRay& parent, RayKind kind, RayCounts& counts) {
  b.next.push(org, dir, weight, parent.sample);
  counts.reflection += kind == RayKind::reflection;
  counts.refraction += kind == RayKind::refraction;
}

// The ray reflected at s about the normal n, of weight w.
MLIB_INLINE void push_reflected(const PathRay& r, const SurfacePoint& s, const vec4& n,
                                const vec4& w, float min_weight, Batches& b, RayCounts& counts) {
  if (heavy_enough(w, min_weight))
    push_path_ray(b, s.above, reflect(r.ray.dir, n), w, r, RayKind::reflection, counts);
}

// The ray transmitted at s through the normal n into a medium of index `ior` (or out of it,
// when the ray leaves the surface's inside), of weight w: refracted, or reflected on total
// internal reflection. A refracted ray starts below the surface.
MLIB_INLINE void push_refracted(const CompiledScene& sc, const PathRay& r, const SurfacePoint& s,
                                const vec4& n, float ior, const vec4& w, float min_weight,
                                Batches& b, RayCounts& counts) {
  if (!heavy_enough(w, min_weight)) return;
  const float eta = s.entering ? 1.0f / ior : ior;
  vec4 t;
  if (refract(r.ray.dir, n, eta, t))
    push_path_ray(b, offset_ray_origin(s.p, -s.ng, sc.offset_scale), t, w, r,
                  RayKind::refraction, counts);
  else
    push_path_ray(b, s.above, reflect(r.ray.dir, n), w, r, RayKind::reflection, counts);
}

}  // namespace rt2::RT2_ISA
