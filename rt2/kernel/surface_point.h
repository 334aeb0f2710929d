// rt2/kernel/surface_point.h — a hit made into what shading reads: the surface point and
// its normals, facing the ray, with where secondary rays start (offset.h), and the texture
// coordinates there; per kind of primitive.
//
// The point is computed from the hit's barycentrics (triangles) or re-projected onto the
// surface (spheres, planes): precise to a few ulps, see geometry/offset.h. A triangle of an
// instance is first placed in the world (world_triangle), its shading normals turned by the
// inverse transpose.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "rt2/kernel/kernel.h"

#include "rt2/bvh/accel.h"
#include "rt2/geometry/offset.h"
#include "rt2/geometry/ray.h"

namespace rt2::RT2_ISA {

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
  std::uint32_t instance;
  float t, u, v;
};

// Triangle i as it lies in the world: in instance `instance` (kNoInstance: the world's own)
// its vertices transformed, and its normal turned back when the instance mirrors.
inline Triangle world_triangle(const Accel& acc, std::uint32_t i, std::uint32_t instance) {
  const Triangle& t = acc.tris[i];
  if (instance == kNoInstance || acc.instances[instance].identity) return t;
  const TracedInstance& in = acc.instances[instance];
  Triangle w = Triangle::make(in.to_world.point(t.v0), in.to_world.point(t.v1),
                              in.to_world.point(t.v2));
  if (in.mirror) w.n = -w.n;
  return w;
}

inline SurfacePoint surface_at(const Accel& acc, const Ray& ray, const Hit& h,
                               float offset_scale) {
  SurfacePoint s;
  const std::uint32_t i = prim_index(h.prim);
  if (prim_tag(h.prim) == kTriangleTag && h.instance != kNoInstance &&
      !acc.instances[h.instance].identity) {
    const Triangle tri = world_triangle(acc, i, h.instance);
    s.p = tri.point(h.u, h.v);
    s.ng = normalize(tri.n);
    if (acc.tri_normals.empty()) {
      s.ns = s.ng;
    } else {
      // each vertex's normal placed, as the loaders place a flattened mesh's, then interpolated
      const auto& n = acc.tri_normals[i];
      const AffineColumns& to_world = acc.instances[h.instance].normals;
      s.ns = normalize((1.0f - h.u - h.v) * normalize(to_world.direction(n[0])) +
                       h.u * normalize(to_world.direction(n[1])) +
                       h.v * normalize(to_world.direction(n[2])));
    }
  } else if (prim_tag(h.prim) == kTriangleTag) {
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
  s.material = acc.material_of(h.prim, h.instance);
  s.prim = h.prim;
  s.instance = h.instance;
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
    const Triangle tri = world_triangle(acc, i, s.instance);
    const float world_area = std::sqrt(float(dot(tri.n, tri.n)));
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

}  // namespace rt2::RT2_ISA
