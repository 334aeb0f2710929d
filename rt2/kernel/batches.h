// rt2/kernel/batches.h — the data the render kernel's stages pass along (tracer.h): rays of the
// ray tree, their hits' surface points, the shadow rays and light lists of a batch. Rays
// and shadow rays are kept as columns (columns.h), for the SIMD stages.
//
// Compiled per instruction set like the kernel (the code lives in rt2::RT2_ISA).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "rt2/bvh/accel.h"
#include "rt2/scene/light.h"
#include "rt2/lights/cluster_visibility.h"
#include "rt2/kernel/columns.h"
#include "rt2/geometry/offset.h"
#include "rt2/geometry/ray.h"
#include "rt2/render/renderer.h"

namespace rt2::RT2_ISA {
namespace detail {

// A batch whose first eight columns are its rays (origin x y z w, then direction x y z w):
// ray i, and the rays as RayColumns.
template <int C>
MLIB_INLINE Ray ray_in(const Columns<C>& c, std::size_t i) {
  return Ray(vec4(c.f(0)[i], c.f(1)[i], c.f(2)[i], c.f(3)[i]),
             vec4(c.f(4)[i], c.f(5)[i], c.f(6)[i], c.f(7)[i]));
}
template <int C>
RayColumns ray_columns(const Columns<C>& c) {
  return {{c.f(0), c.f(1), c.f(2), c.f(3)}, {c.f(4), c.f(5), c.f(6), c.f(7)}};
}

// A ray of the ray tree, and whose sample it adds to, as one-ray code reads it from a batch
// (PathRays). A ray's depth is its batch's, and its kind is counted when it is spawned.
struct PathRay {
  Ray ray;
  // The product of the reflection / transmission factors along the path, per channel: Kr
  // and Kt (the same in every channel) for Phong, Fresnel-weighted colours for physically
  // based surfaces (w = 0).
  vec4 w;
  std::uint32_t sample;  // index into the block's sample colours
  MLIB_INLINE const vec4& weight() const { return w; }
};

// The rays of a batch, PathRay's fields as columns (columns.h): operator[] gives one ray
// whole; the packet queries and the shading lanes read the columns.
class PathRays {
 public:
  enum Column { kOrg = 0, kDir = 4, kWeight = 8, kSample = 11, kColumns = 12 };  // x y z w / r g b
  static_assert(kOrg == 0 && kDir == 4);  // ray_in, ray_columns

  std::size_t size() const { return c_.size(); }
  bool empty() const { return c_.empty(); }
  void clear() { c_.clear(); }

  MLIB_INLINE PathRay operator[](std::size_t i) const { return PathRay{ray(i), weight(i), c_.u(kSample)[i]}; }
  MLIB_INLINE vec4 weight(std::size_t i) const {
    return vec4(c_.f(kWeight)[i], c_.f(kWeight + 1)[i], c_.f(kWeight + 2)[i]);
  }
  MLIB_INLINE Ray ray(std::size_t i) const { return ray_in(c_, i); }
  // Appends a ray (the weight's w is not kept).
  MLIB_INLINE void push(const vec4& org, const vec4& dir, const vec4& weight, std::uint32_t sample) {
    const std::size_t i = c_.extend(1);
    for (int a = 0; a < 4; ++a) {
      c_.f(kOrg + a)[i] = org[a];
      c_.f(kDir + a)[i] = dir[a];
    }
    for (int k = 0; k < 3; ++k) c_.f(kWeight + k)[i] = weight[k];
    c_.u(kSample)[i] = sample;
  }

  // Appends n <= 4 rays of weight 1 from `org` (a row of a packet of primary rays): their
  // directions dir[0 ... n - 1] and samples sample[0 ... n - 1], four lanes at a time.
  MLIB_INLINE void push_row(const vec4& org, const vec4 (&dir)[4], const std::uint32_t (&sample)[4],
                            int n) {
    namespace simd = mlib::simd;
    c_.reserve(c_.size() + 4);
    const std::size_t i = c_.size();
    simd::f4 x, y, z, w;
    simd::transpose4(org.m128(), org.m128(), org.m128(), org.m128(), x, y, z, w);
    simd::store(c_.f(kOrg) + i, x), simd::store(c_.f(kOrg + 1) + i, y);
    simd::store(c_.f(kOrg + 2) + i, z), simd::store(c_.f(kOrg + 3) + i, w);
    simd::transpose4(dir[0].m128(), dir[1].m128(), dir[2].m128(), dir[3].m128(), x, y, z, w);
    simd::store(c_.f(kDir) + i, x), simd::store(c_.f(kDir + 1) + i, y);
    simd::store(c_.f(kDir + 2) + i, z), simd::store(c_.f(kDir + 3) + i, w);
    for (int k = 0; k < 3; ++k) simd::store(c_.f(kWeight + k) + i, simd::set1(1.0f));
    for (int k = 0; k < 4; ++k) c_.u(kSample)[i + std::size_t(k)] = sample[k];
    c_.extend(std::size_t(n));
  }

  RayColumns rays() const { return ray_columns(c_); }
  Columns<kColumns>& columns() { return c_; }
  const Columns<kColumns>& columns() const { return c_; }

 private:
  Columns<kColumns> c_;
};

// Whether a ray of weight w is worth tracing: its largest channel exceeds `min_weight`.
MLIB_INLINE bool heavy_enough(const vec4& w, float min_weight) {
  return mlib::hmax3(w) > min_weight;
}

// The shadow rays of a batch as columns (columns.h): each ray with the light's unshadowed
// term at the point it leaves (weight x (Kd (L·N) + Ks (R·V)^n) x light radiance), the
// distance to the light, its sample, its light (index into CompiledScene::lights) and
// whether it is proven to pass whole (cluster_visibility.h: then not traced).
//
// The batch keeps its shape as rays are added: whether its lights never decrease along it
// (one light, say: its runs are then its groups by light, and trace_shadows need not sort),
// the ends of its runs of one light, and whether some ray is proven unoccluded.
class ShadowRays {
 public:
  enum Column {
    kOrg = 0, kDir = 4, kTerm = 8, kDistance = 11, kSample = 12, kLight = 13, kUnoccluded = 14,
    kColumns = 15
  };
  static_assert(kOrg == 0 && kDir == 4);  // ray_in, ray_columns

  std::size_t size() const { return c_.size(); }
  bool empty() const { return c_.empty(); }
  void clear() {
    c_.clear();
    run_ends_.clear();
    grouped_ = true;
    some_unoccluded_ = false;
  }

  // Appends a shadow ray (the term's w is not kept).
  MLIB_INLINE void push(const vec4& org, const vec4& dir, float distance, const vec4& term,
                        std::uint32_t light, std::uint32_t sample, bool unoccluded) {
    const std::size_t i = extend(light, 1, unoccluded);
    for (int a = 0; a < 4; ++a) {
      c_.f(kOrg + a)[i] = org[a];
      c_.f(kDir + a)[i] = dir[a];
    }
    for (int k = 0; k < 3; ++k) c_.f(kTerm + k)[i] = term[k];
    c_.f(kDistance)[i] = distance;
    c_.u(kSample)[i] = sample;
    c_.u(kLight)[i] = light;
    c_.u(kUnoccluded)[i] = unoccluded;
  }
  // Adds n rays to `light` whose columns the caller fills (kLight and kUnoccluded
  // included); returns the index of the first.
  MLIB_INLINE std::size_t extend(std::uint32_t light, std::size_t n, bool unoccluded) {
    if (!c_.empty() && n > 0) {
      const std::uint32_t last = c_.u(kLight)[c_.size() - 1];
      grouped_ = grouped_ && last <= light;
      if (last != light) run_ends_.push_back(static_cast<std::uint32_t>(c_.size()));
    }
    some_unoccluded_ = some_unoccluded_ || (unoccluded && n > 0);
    return c_.extend(n);
  }

  MLIB_INLINE Ray ray(std::size_t i) const { return ray_in(c_, i); }
  MLIB_INLINE vec4 term(std::size_t i) const {
    return vec4(c_.f(kTerm)[i], c_.f(kTerm + 1)[i], c_.f(kTerm + 2)[i]);
  }
  float distance(std::size_t i) const { return c_.f(kDistance)[i]; }
  const float* distances() const { return c_.f(kDistance); }
  std::uint32_t sample(std::size_t i) const { return c_.u(kSample)[i]; }
  std::uint32_t light(std::size_t i) const { return c_.u(kLight)[i]; }
  bool unoccluded(std::size_t i) const { return c_.u(kUnoccluded)[i] != 0; }

  RayColumns rays() const { return ray_columns(c_); }
  Columns<kColumns>& columns() { return c_; }

  // The shape (see above).
  bool grouped() const { return grouped_; }
  bool some_unoccluded() const { return some_unoccluded_; }
  const std::vector<std::uint32_t>& run_ends() const { return run_ends_; }

 private:
  Columns<kColumns> c_;
  bool grouped_ = true, some_unoccluded_ = false;
  std::vector<std::uint32_t> run_ends_;
};

// What shading needs to know about a hit.
struct SurfacePoint {
  vec4 p;                   // on the surface, computed precisely (see offset.h)
  vec4 ng;                  // unit geometric normal, on the side the ray came from
  vec4 ns;                  // unit shading normal, same side
  vec4 above;               // p moved off the surface along ng: where shadow and reflected
                            // rays start (offset.h)
  bool entering;            // the ray hit the outside (against the outward normal)
  std::uint32_t material;
  // The hit itself, for what only some materials need (texture coordinates: texcoords_at).
  PrimRef prim;
  float t, u, v;
};

// The lights a shading point considers: CompiledScene::lights[index[k]] for k < count, or
// every light (index null, count = all).
struct LightList {
  const std::uint32_t* index = nullptr;
  std::size_t count = 0;
  // Per light of the list, whether every shadow ray from the list's cluster to it provably
  // meets nothing (cluster_visibility.h); null: nothing proven.
  const std::uint8_t* sees = nullptr;
  std::uint32_t operator[](std::size_t k) const {
    return index ? index[k] : static_cast<std::uint32_t>(k);
  }
};

// A shadow ray's light and its index in the batch, for grouping the batch by light.
struct LightRay {
  std::uint32_t light, ray;
};

// The batches of one thread, reused from block to block (no allocation once grown).
struct Batches {
  PathRays rays, next;
  std::vector<std::uint32_t> packet_begin;  // the primary batch's packets (generate)
  std::vector<Hit> hits;                    // per ray of `rays`
  std::vector<SurfacePoint> points;         // per ray of `rays` that hit
  // Light lists: list k is light_items[list_begin[k], list_begin[k + 1]); the hit of ray
  // i uses list list_of[i]. No lists: every hit considers every light.
  std::vector<std::uint32_t> light_items, list_begin, list_of;
  std::vector<std::uint8_t> list_sees;  // parallel to light_items (see LightList::sees)
  ClusterVisibility visibility;
  std::vector<std::uint32_t> to_trace;  // the shadow rays to trace
  std::vector<std::uint32_t> found;     // one query's answer
  std::vector<float> depth;             // clustered culling: per ray, its hit's depth
  std::vector<Aabb> cluster_bounds;     // clustered culling: per slice
  ShadowRays shadows;
  std::vector<float> passed;              // per shadow ray: the light that passes
  std::vector<std::uint32_t> by_light;    // shadow rays grouped by light, in batch order
  std::vector<std::uint32_t> light_begin;
  std::vector<LightRay> light_rays;
  std::vector<vec4> colors;

};

inline SurfacePoint surface_at(const Accel& acc, const Ray& ray, const Hit& h,
                               float offset_scale) {
  SurfacePoint s;
  const std::uint32_t i = prim_index(h.prim);
  if (prim_tag(h.prim) == kTriangleTag) {
    const Triangle& tri = acc.tris[i];
    s.p = tri.point(h.u, h.v);  // from barycentrics: precise, see offset.h
    s.ng = normalize(tri.n);
    if (acc.tri_normals.empty()) {
      s.ns = s.ng;
    } else {
      const auto& n = acc.tri_normals[i];
      s.ns = normalize((1.0f - h.u - h.v) * n[0] + h.u * n[1] + h.v * n[2]);
    }
  } else if (prim_tag(h.prim) == kSphereTag) {
    const Sphere& sp = acc.spheres[i];
    s.ng = sphere_normal(sp, ray.at(h.t));
    s.p = sp.center + s.ng * sp.radius;  // re-projected onto the surface
    s.ns = s.ng;
  } else {
    const Plane& pl = acc.planes[i];
    const vec4 q = ray.at(h.t);
    s.p = q - pl.n * (float(dot(q, pl.n)) + pl.d);  // projected onto the plane
    s.ng = s.ns = pl.n;
  }
  s.material = acc.material_of(h.prim);
  s.prim = h.prim;
  s.t = h.t;
  s.u = h.u;
  s.v = h.v;
  s.entering = dot(ray.dir, s.ng) < 0.0f;
  if (!s.entering) {
    s.ng = -s.ng;
    s.ns = -s.ns;
  }
  if (!(dot(s.ns, ray.dir) < 0.0f)) s.ns = s.ng;  // an interpolated normal facing away
  s.above = offset_ray_origin(s.p, s.ng, offset_scale);
  return s;
}

// Appends a child of `parent` to the next batch, and counts it by kind.
MLIB_INLINE void push_path_ray(Batches& b, const vec4& org, const vec4& dir, const vec4& weight,
                               const PathRay& parent, RayKind kind, RayCounts& counts) {
  b.next.push(org, dir, weight, parent.sample);
  counts.reflection += kind == RayKind::reflection;
  counts.refraction += kind == RayKind::refraction;
}

// Appends a shadow ray from `origin` towards `light` (index li), unit direction l, `dist`
// away, carrying weight x (term x the light's radiance and range window), `term` being the
// unshadowed contribution per unit radiance (in that order, as before: the same bits).
MLIB_INLINE void push_shadow_ray(Batches& b, const vec4& origin, const vec4& l, float dist,
                                 const vec4& weight, const vec4& term, const Light& light,
                                 std::uint32_t li, std::uint32_t sample, bool unoccluded) {
  b.shadows.push(origin, l, dist,
                 weight * (term * (light.has_range() ? light.radiance() * range_window(light, dist)
                                                     : light.radiance())),
                 li, sample, unoccluded);
}

// The texture coordinates (u, v) at a surface point, and how many texture units one world
// unit spans there (for the footprint of a lookup): triangles interpolate their vertices'
// (0 without), spheres map longitude to u and latitude to v (v = 1 at the top, +y), planes
// take their point's coordinates along two axes in the plane.
struct TexturePoint {
  float u = 0.0f, v = 0.0f;
  float per_world = 0.0f;
};

// `origin` is where the coordinates' origin is in the world (CompiledScene::origin): a
// plane's coordinates are the world's, so that recentring the scene on the camera does not
// move its texture (as the checker's).
inline TexturePoint texcoords_at(const Accel& acc, const SurfacePoint& s, const vec4& origin) {
  TexturePoint tp;
  const std::uint32_t i = prim_index(s.prim);
  if (prim_tag(s.prim) == kTriangleTag) {
    if (acc.tri_texcoords.empty()) return tp;
    const auto& c = acc.tri_texcoords[i];
    const float w = 1.0f - s.u - s.v;
    tp.u = w * c[0][0] + s.u * c[1][0] + s.v * c[2][0];
    tp.v = w * c[0][1] + s.u * c[1][1] + s.v * c[2][1];
    // sqrt(texture area / world area) of the triangle
    const float uv_area = std::fabs((c[1][0] - c[0][0]) * (c[2][1] - c[0][1]) -
                                    (c[2][0] - c[0][0]) * (c[1][1] - c[0][1]));
    const float world_area = std::sqrt(float(dot(acc.tris[i].n, acc.tris[i].n)));
    tp.per_world = world_area > 0.0f ? std::sqrt(uv_area / world_area) : 0.0f;
  } else if (prim_tag(s.prim) == kSphereTag) {
    const Sphere& sp = acc.spheres[i];
    const vec4 n = (s.p - sp.center) / sp.radius;
    tp.u = 0.5f + std::atan2(float(n[0]), float(n[2])) * (0.5f / std::numbers::pi_v<float>);
    tp.v = 1.0f - std::acos(std::clamp(float(n[1]), -1.0f, 1.0f)) / std::numbers::pi_v<float>;
    tp.per_world = 1.0f / (std::numbers::pi_v<float> * sp.radius);
  } else {
    const Plane& pl = acc.planes[i];
    // two axes in the plane: the world axis least aligned with n, made orthogonal
    const vec4 a = std::fabs(float(pl.n[1])) < 0.9f ? vec4(0, 1, 0) : vec4(1, 0, 0);
    const vec4 x = normalize(cross(a, pl.n));
    const vec4 y = cross(pl.n, x);
    const vec4 world = s.p + origin;
    tp.u = dot(world, x);
    tp.v = dot(world, y);
    tp.per_world = 1.0f;
  }
  return tp;
}

}  // namespace detail
}  // namespace rt2::RT2_ISA
