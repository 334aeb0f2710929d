// rt2/tracer.h — the per-pixel kernel: Whitted ray tracing with Phong shading (thesis 3.1,
// 3.2), as a template over the triangle test.
//
// Compiled per instruction set (rt2/isa.h) by isa_kernels.cpp: the code lives in
// rt2::RT2_ISA. Materials decide reflection, refraction and highlights at run time (a
// kernel compiled per combination of scene features measured about 1 % faster, inside the
// noise, so it was dropped). Recursion is
// iterative: a pixel's rays form a tree (reflection and refraction split it), walked
// depth-first with an explicit stack whose size grows with the recursion depth, so a
// depth of 10,000 cannot overflow the thread's stack. A ray's contribution is its weight
// (the product of the Kr / Kt factors along its path) times the local Phong colour where
// it lands; a child ray is traced only while depth < settings.depth and its weight
// exceeds settings.min_weight.
#pragma once

#include <cmath>
#include <vector>

#include "rt2/offset.h"
#include "rt2/optics.h"
#include "rt2/query.h"
#include "rt2/render.h"

namespace rt2::RT2_ISA {
namespace detail {

struct Task {
  Ray ray;
  float weight;
  int depth;
  RayKind kind;
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
  s.entering = dot(ray.dir, s.ng) < 0.0f;
  if (!s.entering) {
    s.ng = -s.ng;
    s.ns = -s.ns;
  }
  if (!(dot(s.ns, ray.dir) < 0.0f)) s.ns = s.ng;  // an interpolated normal facing away
  s.above = offset_ray_origin(s.p, s.ng, offset_scale);
  return s;
}

// I_local = Ka I_amb + sum over lights that reach p of Kd I (L·N) + Ks I (R·V)^n, with I
// attenuated by transparent occluders (thesis 3.2; SPEC "Shading").
template <bool Watertight>
inline vec4 shade_local(const Renderer& r, const Ray& ray, const SurfacePoint& s,
                        RayCounts& counts) {
  const Scene& sc = r.scene();
  const Material& m = sc.materials[s.material];
  vec4 color = m.ambient * sc.ambient;
  if (sc.lights.empty()) return color;
  const vec4 kd = m.diffuse_at(s.p + sc.origin);  // textures live in world coordinates
  const vec4& origin = s.above;
  const vec4 view = -ray.dir;
  for (const Light& light : sc.lights) {
    const vec4 to = light.position - origin;
    const float dist = std::sqrt(float(dot(to, to)));
    const vec4 l = to / dist;
    if (!(dot(l, s.ng) > 0.0f)) continue;  // the light is behind the surface (or at p)
    const float n_dot_l = dot(s.ns, l);
    if (!(n_dot_l > 0.0f)) continue;
    ++counts.shadow;
    const float passed =
        transmittance<Watertight>(r.accel(), sc.materials, Ray(origin, l), 0.0f, dist);
    if (passed == 0.0f) continue;
    const vec4 li = light.radiance() * passed;
    color += kd * li * n_dot_l;
    if (m.has_specular()) {
      const float r_dot_v = dot(2.0f * n_dot_l * s.ns - l, view);  // R = reflect(-L, N)
      if (r_dot_v > 0.0f) color += m.specular * li * std::pow(r_dot_v, m.shininess);
    }
  }
  return color;
}

// The colour seen along `primary`: the sum over the ray tree of weight x local colour.
template <bool Watertight>
inline vec4 trace(const Renderer& r, const Ray& primary, std::vector<Task>& stack,
                  RayCounts& counts) {
  const RenderSettings& st = r.settings();
  const Scene& sc = r.scene();
  vec4 color;
  stack.clear();
  stack.push_back({primary, 1.0f, 0, RayKind::primary});
  while (!stack.empty()) {
    const Task task = stack.back();
    stack.pop_back();
    counts.reflection += task.kind == RayKind::reflection;
    counts.refraction += task.kind == RayKind::refraction;
    const Hit h = closest_hit<Watertight>(r.accel(), task.ray, 0.0f, kInfinity);
    if (!h.found()) {
      color += task.weight * sc.background;
      continue;
    }
    const SurfacePoint s = surface_at(r.accel(), task.ray, h, r.offset_scale());
    color += task.weight * shade_local<Watertight>(r, task.ray, s, counts);
    if (task.depth >= st.depth) continue;
    const Material& m = sc.materials[s.material];
    if (m.transparency > 0.0f) {
      const float w = task.weight * m.transparency;
      if (w > st.min_weight) {
        const float eta = s.entering ? 1.0f / m.ior : m.ior;
        vec4 t;
        if (refract(task.ray.dir, s.ns, eta, t))
          stack.push_back({Ray(offset_ray_origin(s.p, -s.ng, r.offset_scale()), t), w,
                           task.depth + 1, RayKind::refraction});
        else  // total internal reflection: the transmitted share is reflected
          stack.push_back(
              {Ray(s.above, reflect(task.ray.dir, s.ns)), w, task.depth + 1, RayKind::reflection});
      }
    }
    if (m.reflectivity > 0.0f) {
      const float w = task.weight * m.reflectivity;
      if (w > st.min_weight)
        stack.push_back(
            {Ray(s.above, reflect(task.ray.dir, s.ns)), w, task.depth + 1, RayKind::reflection});
    }
  }
  return color;
}

}  // namespace detail

template <bool Watertight>
void render_rows_kernel(const Renderer& r, int y0, int y1, Image& image, RayCounts& counts) {
  const RenderSettings& st = r.settings();
  const Camera& cam = r.scene().camera;
  const auto& offsets = r.offsets();
  const float n = float(offsets.size());
  std::vector<detail::Task> stack;  // reused by every pixel of these rows
  stack.reserve(64);
  RayCounts local;
  for (int y = y0; y < y1; ++y) {
    float* out = image.row(y);
    for (int x = 0; x < st.width; ++x) {
      // Compensated (Kahan) summation: 1024 subpixels average to within an ulp, where a
      // plain running sum would lose ~sqrt(N) ulps.
      vec4 sum, carry;
      for (const SubpixelOffset& o : offsets) {
        const vec4 c = detail::trace<Watertight>(
            r, cam.ray(float(x) + o.x, float(y) + o.y, st.width, st.height), stack, local);
        const vec4 y_ = c - carry;
        const vec4 t = sum + y_;
        carry = (t - sum) - y_;
        sum = t;
      }
      sum /= n;
      if (!(std::isfinite(sum[0]) && std::isfinite(sum[1]) && std::isfinite(sum[2]))) {
        ++local.nonfinite_pixels;  // never expected: counted so that tests can insist on 0
        sum = vec4();
      }
      out[3 * x + 0] = sum[0];
      out[3 * x + 1] = sum[1];
      out[3 * x + 2] = sum[2];
    }
  }
  local.primary += std::uint64_t(y1 - y0) * std::uint64_t(st.width) * offsets.size();
  counts += local;
}

}  // namespace rt2::RT2_ISA
