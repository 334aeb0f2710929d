// rt2/accel.h — a scene's geometry compiled for rendering: a BVH over spheres and
// triangles, with the primitives copied into leaf order, plus the unbounded planes.
//
// Primitives are kept per kind in contiguous arrays (no virtual call per test): a leaf's
// entries in `refs` carry a kind tag and an index into `tris` or `spheres`, and since the
// arrays are in leaf order, a leaf's triangles are consecutive in memory. `closest_hit`
// and `transmittance` are templates over the scene's feature bits, so a scene without
// spheres has no sphere test in its kernel.
#pragma once

#include <array>
#include <cmath>
#include <type_traits>
#include <vector>

#include "rt2/bvh/build.h"
#include "rt2/bvh/traverse.h"
#include "rt2/features.h"
#include "rt2/geometry/plane.h"
#include "rt2/geometry/sphere.h"
#include "rt2/geometry/triangle.h"
#include "rt2/material.h"

namespace rt2 {

struct Scene;

struct Accel {
  Bvh bvh;
  std::vector<PrimRef> refs;  // one per leaf entry, in leaf order
  std::vector<Triangle> tris;
  std::vector<std::uint32_t> tri_materials;
  std::vector<std::array<vec4, 3>> tri_normals;  // per-vertex normals; empty if all flat
  std::vector<Sphere> spheres;
  std::vector<std::uint32_t> sphere_materials;
  std::vector<Plane> planes;
  std::vector<std::uint32_t> plane_materials;

  // Builds the BVH with `config` and lays the primitives out in leaf order.
  static Accel build(const Scene& scene, const BvhConfig& config);

  std::uint32_t material_of(PrimRef p) const {
    const std::uint32_t i = prim_index(p);
    switch (prim_tag(p)) {
      case kTriangleTag: return tri_materials[i];
      case kSphereTag: return sphere_materials[i];
      default: return plane_materials[i];
    }
  }
};

// The per-ray form the triangle test needs: the watertight test's sheared ray (computed
// once per query), or nothing for the fast test.
struct NoShear {
  explicit NoShear(const Ray&) {}
};
template <unsigned F>
using ShearFor = std::conditional_t<has_feature<F, kWatertight>, WatertightRay, NoShear>;

template <unsigned F>
inline bool intersect_triangle(const Triangle& tri, const Ray& ray, const ShearFor<F>& shear,
                               float t_min, float t_max, float& t, float& u, float& v) {
  if constexpr (has_feature<F, kWatertight>)
    return intersect_watertight(tri, shear, t_min, t_max, t, u, v);
  else
    return intersect(tri, ray, t_min, t_max, t, u, v);
}

// The leaf test shared by both queries: calls on_hit(ref, t, u, v) for every primitive of
// the leaf hit inside (t_min, t_max); on_hit returns true to stop. With Closest, each hit
// shrinks t_max so that later primitives must be nearer.
template <unsigned F, bool Closest, class OnHit>
inline bool test_leaf(const Accel& acc, const Ray& ray, const ShearFor<F>& shear,
                      std::uint32_t first, std::uint32_t count, float t_min, float t_max,
                      OnHit&& on_hit) {
  for (std::uint32_t i = first; i < first + count; ++i) {
    const PrimRef ref = acc.refs[i];
    const std::uint32_t k = prim_index(ref);
    float t, u = 0.0f, v = 0.0f;
    bool hit = false;
    if constexpr (has_feature<F, kTriangles> && has_feature<F, kSpheres>) {
      hit = prim_tag(ref) == kTriangleTag
                ? intersect_triangle<F>(acc.tris[k], ray, shear, t_min, t_max, t, u, v)
                : intersect(acc.spheres[k], ray, t_min, t_max, t);
    } else if constexpr (has_feature<F, kTriangles>) {
      hit = intersect_triangle<F>(acc.tris[k], ray, shear, t_min, t_max, t, u, v);
    } else if constexpr (has_feature<F, kSpheres>) {
      hit = intersect(acc.spheres[k], ray, t_min, t_max, t);
    }
    if (hit) {
      if (on_hit(ref, t, u, v)) return true;
      if constexpr (Closest) t_max = t;
    }
  }
  return false;
}

// The nearest hit in (t_min, t_max) over planes and the BVH.
template <unsigned F>
inline Hit closest_hit(const Accel& acc, const Ray& ray, float t_min, float t_max) {
  Hit h;
  h.t = t_max;
  if constexpr (has_feature<F, kPlanes>) {
    for (std::uint32_t i = 0; i < acc.planes.size(); ++i) {
      float t;
      if (intersect(acc.planes[i], ray, t_min, h.t, t)) {
        h.t = t;
        h.prim = kPlaneTag | i;
      }
    }
  }
  if constexpr (has_feature<F, kTriangles> || has_feature<F, kSpheres>) {
    const RayPre pre(ray);
    const ShearFor<F> shear(ray);
    traverse<false>(acc.bvh, pre, t_min, h.t, [&](std::uint32_t first, std::uint32_t count, float& t_max_) {
      return test_leaf<F, true>(acc, ray, shear, first, count, t_min, t_max_,
                          [&](PrimRef ref, float t, float u, float v) {
                            t_max_ = t;
                            h.prim = ref;
                            h.u = u;
                            h.v = v;
                            return false;
                          });
    });
  }
  if (!h.found()) h.t = kInfinity;
  return h;
}

// How much light passes along the segment (t_min, t_max) of `ray`: 1 when nothing is in
// the way, 0 when an opaque surface is, and the product of the transparencies Kt of every
// surface crossed otherwise (each crossing counts once: a glass sphere crossed through
// attenuates twice, as a closed glass mesh does). Without kRefraction in F every surface
// is opaque and this is a plain any-hit query that stops at the first hit.
template <unsigned F>
inline float transmittance(const Accel& acc, const std::vector<Material>& materials,
                           const Ray& ray, float t_min, float t_max) {
  float tr = 1.0f;
  // Returns true when no light can pass any more.
  auto crossing = [&](std::uint32_t material) {
    if constexpr (!has_feature<F, kRefraction>) {
      (void)material;
      tr = 0.0f;
    } else {
      tr *= materials[material].transparency;
    }
    return tr == 0.0f;
  };
  if constexpr (has_feature<F, kPlanes>) {
    for (std::uint32_t i = 0; i < acc.planes.size(); ++i) {
      float t;
      if (intersect(acc.planes[i], ray, t_min, t_max, t) && crossing(acc.plane_materials[i]))
        return 0.0f;
    }
  }
  if constexpr (has_feature<F, kTriangles> || has_feature<F, kSpheres>) {
    const RayPre pre(ray);
    const ShearFor<F> shear(ray);
    float t_far = t_max;
    traverse<true>(acc.bvh, pre, t_min, t_far, [&](std::uint32_t first, std::uint32_t count, float&) {
      return test_leaf<F, false>(acc, ray, shear, first, count, t_min, t_max,
                          [&](PrimRef ref, float t, float, float) {
                            if (crossing(acc.material_of(ref))) return true;
                            if constexpr (has_feature<F, kSpheres>) {
                              // The far side of a sphere is a second crossing.
                              float t2;
                              if (prim_tag(ref) == kSphereTag &&
                                  intersect(acc.spheres[prim_index(ref)], ray, t, t_max, t2))
                                return crossing(acc.material_of(ref));
                            }
                            return false;
                          });
    });
  }
  return tr;
}

}  // namespace rt2
