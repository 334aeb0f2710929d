// rt2/kernel/phong_lanes.h — Phong shading (phong.h) of up to kHitLanes hits in one SIMD
// pass, structure of arrays: their surface points (surface_point.h), the ambient term, each
// light's term (the shadow rays) and the reflected rays.
//
// Invariant: every lane computes what phong.h computes for one hit, bit for bit: the same
// operations in the same order, vec4's dot product as (x x' + y y') + (z z' + w w') with the
// w lanes the one-hit code carries, normalize's rescaling path per lane, std::pow per lane.
// Each lane's results are emitted in batch order (emit_lane, or emit_lanes where that order
// is kept), so the batches come out as the one-hit code makes them. Which hits: Phong without
// texture or transparency, when every hit considers every light and there are at most
// kMaxLaneLights lights.
#pragma once

#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>

#include "rt2/kernel/kernel.h"

#include "mlib/vfloat.h"
#include "rt2/kernel/batches.h"
#include "rt2/render/compiled_scene.h"
#include "rt2/kernel/plane_sphere_packet_intersect.h"  // dot_dpps, negate
#include "rt2/geometry/offset.h"
#include "rt2/render/renderer.h"

namespace rt2::RT2_ISA {

inline constexpr int kHitLanes = mlib::kWidestLanes;
inline constexpr std::size_t kMaxLaneLights = 8;

// One pass's inputs (gather_lanes) and results.
struct PhongLanes {
  using F = float[kHitLanes];
  using F3 = float[3][kHitLanes];
  // the hit (the ray is read from the batch's columns)
  alignas(64) F t, u, v;
  // per primitive kind (the other lanes hold a copy of one of its lanes)
  alignas(64) F3 v0, v1, v2, tri_n;   // triangles: vertices, unnormalised normal
  alignas(64) F3 n0, n1, n2;          // triangles' vertex normals (without: unused)
  alignas(64) F3 center;              // spheres
  alignas(64) F radius;
  alignas(64) F3 plane_n;             // planes
  alignas(64) F plane_d;
  unsigned triangles = 0, spheres = 0, planes = 0;  // lanes of each kind
  // the material's index (the lanes of one material take its values together), and whether
  // every lane has the same
  std::uint32_t material_index[kHitLanes];
  bool one_material = false;
  // results
  alignas(64) F3 above, ambient_term, reflect_dir, reflect_weight;
  alignas(64) float reflect_dir_w[kHitLanes];
  unsigned reflects = 0;  // lanes that spawn a reflected ray
  struct LightLanes {
    alignas(64) F3 dir, term;
    alignas(64) F dir_w, distance;
    unsigned lit = 0, in_range = 0;
  };
  LightLanes light[kMaxLaneLights];

  // Lane l's ambient term, weighted.
  MLIB_INLINE vec4 ambient(int l) const {
    return vec4(ambient_term[0][l], ambient_term[1][l], ambient_term[2][l]);
  }

  // Before a pass's lanes are gathered.
  void clear_kinds() {
    triangles = spheres = planes = 0;
    one_material = false;
  }
};

namespace lanes {

namespace simd = mlib::simd;

// Lanes 4 j ... 4 j + 3 of x, y, z from the first three lanes of four vec4s.
MLIB_INLINE void put4(simd::f4 v0, simd::f4 v1, simd::f4 v2, simd::f4 v3, float* x, float* y,
                      float* z, int j) {
  simd::f4 a, b, c, w;
  simd::transpose4(v0, v1, v2, v3, a, b, c, w);
  simd::store(x + 4 * j, a);
  simd::store(y + 4 * j, b);
  simd::store(z + 4 * j, c);
}
MLIB_INLINE void put4(simd::f4 v0, simd::f4 v1, simd::f4 v2, simd::f4 v3,
                      float (&a)[3][kHitLanes], int j) {
  put4(v0, v1, v2, v3, a[0], a[1], a[2], j);
}

}  // namespace lanes

// The hits of lanes [first, end) of the batch into p (lanes past the batch repeat its last
// hit), four lanes at a time.
inline void gather_hits(const Batches& b, std::size_t first, std::size_t end, PhongLanes& p) {
  namespace simd = mlib::simd;
  for (int j = 0; j < kHitLanes / 4; ++j) {
    const Hit* h[4];
    for (int k = 0; k < 4; ++k) h[k] = &b.hits[std::min(first + std::size_t(4 * j + k), end - 1)];
    lanes::put4(simd::load_xyz0(&h[0]->t), simd::load_xyz0(&h[1]->t), simd::load_xyz0(&h[2]->t),
                simd::load_xyz0(&h[3]->t), p.t, p.u, p.v, j);
  }
}

// Gathers the hits of rays [first, end) of the batch (at most kHitLanes) that take the
// lanes into p, four lanes at a time (a transpose of four vec4s per quantity), or, when
// every ray hit one primitive, its data broadcast; returns their lanes. Lanes past `end`,
// and the fields of other kinds, hold copies of a valid lane.
inline unsigned gather_lanes(const CompiledScene& sc, const Batches& b, std::size_t first,
                             std::size_t end, PhongLanes& p) {
  namespace simd = mlib::simd;
  const Accel& acc = sc.accel;
  p.clear_kinds();
  const int n = static_cast<int>(end - first);
  const Hit* hits = b.hits.data() + first;
  // Every lane on one primitive (a floor, a sphere in view: most passes of a frame): its
  // material and data once, broadcast.
  const PrimRef prim0 = hits[0].prim;
  bool uniform = prim0 != kNoHit && hits[0].instance == kNoInstance;
  for (int l = 1; l < n; ++l) uniform &= hits[l].prim == prim0 && hits[l].instance == kNoInstance;
  if (uniform) {
    const std::uint32_t material = acc.material_of(prim0);
    if (!sc.plain_phong[material]) return 0;
    const unsigned active = (1u << n) - 1;  // n <= kHitLanes <= 16
    for (int l = 0; l < kHitLanes; ++l) p.material_index[l] = material;
    p.one_material = true;
    const std::uint32_t i = prim_index(prim0);
    using V = mlib::vfloat<kHitLanes>;
    const auto fill3 = [](const vec4& x, float (&a)[3][kHitLanes]) {
      for (int c = 0; c < 3; ++c) V::broadcast(x[c]).store(a[c]);
    };
    switch (prim_tag(prim0)) {
      case kTriangleTag: {
        const Triangle& t = acc.tris[i];
        p.triangles = active;
        fill3(t.v0, p.v0), fill3(t.v1, p.v1), fill3(t.v2, p.v2), fill3(t.n, p.tri_n);
        if (!acc.tri_normals.empty())
          fill3(acc.tri_normals[i][0], p.n0), fill3(acc.tri_normals[i][1], p.n1),
              fill3(acc.tri_normals[i][2], p.n2);
        break;
      }
      case kSphereTag:
        p.spheres = active;
        fill3(acc.spheres[i].center, p.center);
        V::broadcast(acc.spheres[i].radius).store(p.radius);
        break;
      default:
        p.planes = active;
        fill3(acc.planes[i].n, p.plane_n);
        V::broadcast(acc.planes[i].d).store(p.plane_d);
        break;
    }
    gather_hits(b, first, end, p);
    return active;
  }
  unsigned active = 0;
  std::uint32_t kind_index[kHitLanes];
  for (int l = 0; l < kHitLanes; ++l) {
    // A hit on a plain Phong material (CompiledScene::plain_phong) takes lane l; without
    // branches on the material, whose kinds mix in a batch.
    // (a hit in an instance is shaded one by one: surface_at places it in the world)
    const PrimRef prim = l < n && hits[l].instance == kNoInstance ? hits[l].prim : kNoHit;
    if (prim == kNoHit) continue;
    const std::uint32_t material = acc.material_of(prim);
    const unsigned bit = unsigned(sc.plain_phong[material]) << l;
    active |= bit;
    p.material_index[l] = material;
    kind_index[l] = prim_index(prim);
    const PrimRef tag = prim_tag(prim);
    p.triangles |= tag == kTriangleTag ? bit : 0u;
    p.spheres |= tag == kSphereTag ? bit : 0u;
    p.planes |= tag == kPlaneTag ? bit : 0u;
  }
  if (!active) return 0;
  gather_hits(b, first, end, p);
  // Each kind's data (other lanes read the kind's first lane).
  const auto each_quad = [&](unsigned kind, auto&& f) {
    const int any = std::countr_zero(kind);
    for (int j = 0; j < kHitLanes / 4; ++j) {
      std::uint32_t k[4];
      for (int q = 0; q < 4; ++q) k[q] = kind_index[kind >> (4 * j + q) & 1 ? 4 * j + q : any];
      f(j, k);
    }
  };
  if (p.triangles) {
    const Triangle* t = acc.tris.data();
    each_quad(p.triangles, [&](int j, const std::uint32_t* k) {
      lanes::put4(t[k[0]].v0.m128(), t[k[1]].v0.m128(), t[k[2]].v0.m128(), t[k[3]].v0.m128(), p.v0, j);
      lanes::put4(t[k[0]].v1.m128(), t[k[1]].v1.m128(), t[k[2]].v1.m128(), t[k[3]].v1.m128(), p.v1, j);
      lanes::put4(t[k[0]].v2.m128(), t[k[1]].v2.m128(), t[k[2]].v2.m128(), t[k[3]].v2.m128(), p.v2, j);
      lanes::put4(t[k[0]].n.m128(), t[k[1]].n.m128(), t[k[2]].n.m128(), t[k[3]].n.m128(), p.tri_n, j);
      if (acc.tri_normals.empty()) return;
      const auto* nn = acc.tri_normals.data();
      lanes::put4(nn[k[0]][0].m128(), nn[k[1]][0].m128(), nn[k[2]][0].m128(), nn[k[3]][0].m128(), p.n0, j);
      lanes::put4(nn[k[0]][1].m128(), nn[k[1]][1].m128(), nn[k[2]][1].m128(), nn[k[3]][1].m128(), p.n1, j);
      lanes::put4(nn[k[0]][2].m128(), nn[k[1]][2].m128(), nn[k[2]][2].m128(), nn[k[3]][2].m128(), p.n2, j);
    });
  }
  if (p.spheres) {
    const Sphere* sp = acc.spheres.data();
    each_quad(p.spheres, [&](int j, const std::uint32_t* k) {
      lanes::put4(sp[k[0]].center.m128(), sp[k[1]].center.m128(), sp[k[2]].center.m128(),
                  sp[k[3]].center.m128(), p.center, j);
      for (int q = 0; q < 4; ++q) p.radius[4 * j + q] = sp[k[q]].radius;
    });
  }
  if (p.planes) {
    const Plane* pl = acc.planes.data();
    each_quad(p.planes, [&](int j, const std::uint32_t* k) {
      lanes::put4(pl[k[0]].n.m128(), pl[k[1]].n.m128(), pl[k[2]].n.m128(), pl[k[3]].n.m128(),
                  p.plane_n, j);
      for (int q = 0; q < 4; ++q) p.plane_d[4 * j + q] = pl[k[q]].d;
    });
  }
  return active;
}

namespace lanes {

using V = mlib::vfloat<kHitLanes>;
using M = V::bool_type;

MLIB_INLINE void load3(const float (&a)[3][kHitLanes], V* v) {
  for (int c = 0; c < 3; ++c) v[c] = V::load(a[c]);
}
MLIB_INLINE void store3(const V* v, float (&a)[3][kHitLanes]) {
  for (int c = 0; c < 3; ++c) v[c].store(a[c]);
}
MLIB_INLINE void select3(M m, const V* a, const V* b, V* out) {
  for (int c = 0; c < 3; ++c) out[c] = select(m, a[c], b[c]);
}

// a / |a| as vec4's normalize of (a, +0): divided by sqrt(a·a) where that is a normal
// float, and through normalize itself (its rescaling path) in the other lanes of `mask`.
MLIB_INLINE void normalize(V* a, unsigned mask) {
  const V len2 = dot_dpps(a, a, V::broadcast(0.0f));
  const unsigned slow =
      mask & ~mlib::bits((len2 >= V::broadcast(FLT_MIN)) & (len2 <= V::broadcast(FLT_MAX)));
  alignas(64) float in[3][kHitLanes];
  if (slow) store3(a, in);
  const V len = sqrt(len2);
  for (int c = 0; c < 3; ++c) a[c] = a[c] / len;
  if (!slow) return;
  alignas(64) float out[3][kHitLanes];
  store3(a, out);
  for (unsigned m = slow; m; m &= m - 1) {
    const int l = std::countr_zero(m);
    const vec4 n = mlib::normalize(vec4(in[0][l], in[1][l], in[2][l]));
    for (int c = 0; c < 3; ++c) out[c][l] = n[c];
  }
  load3(out, a);
}

// The checker's cell parity of x (floor(x) as a 64-bit integer, & 1): 1 or 0.
MLIB_INLINE V cell_parity(V x) {
  const V f = floor(x);
  const V odd = f - V::broadcast(2.0f) * floor(V::broadcast(0.5f) * f);
  return select(abs(f) < V::broadcast(16777216.0f), odd, V::broadcast(0.0f));
}

}  // namespace lanes

// The pass over the lanes of `active` (filled by gather_lanes) for rays first ... first +
// kHitLanes - 1 of `rays`: p's results, for a scene whose every hit considers all of its
// sc.lights.size() <= kMaxLaneLights lights.
inline void shade_lanes(const CompiledScene& sc, const RenderSettings& st, int depth,
                        unsigned active, const PathRays& rays, std::size_t first, PhongLanes& p) {
  using lanes::V;
  using lanes::M;
  const V zero = V::broadcast(0.0f);
  V org[3], dir[3], weight[3];
  const auto& columns = rays.columns();
  for (int c = 0; c < 3; ++c) {
    org[c] = V::loadu(columns.f(PathRays::kOrg + c) + first);
    dir[c] = V::loadu(columns.f(PathRays::kDir + c) + first);
    weight[c] = V::loadu(columns.f(PathRays::kWeight + c) + first);
  }
  const V t = V::load(p.t), u = V::load(p.u), v = V::load(p.v);
  // The surface point: p, ng, ns (surface_at) per kind, then chosen per lane.
  V pos[3], ng[3], ns[3];
  for (int c = 0; c < 3; ++c) pos[c] = ng[c] = ns[c] = zero;
  V q[3];  // ray.at(t), for spheres and planes
  for (int c = 0; c < 3; ++c) q[c] = org[c] + dir[c] * t;
  if (p.planes) {
    const M is = M::from_bits(p.planes);
    V n[3];
    lanes::load3(p.plane_n, n);
    const V s = dot_dpps(q, n, zero) + V::load(p.plane_d);
    V x[3];
    for (int c = 0; c < 3; ++c) x[c] = q[c] - n[c] * s;
    lanes::select3(is, x, pos, pos);
    lanes::select3(is, n, ng, ng);
    lanes::select3(is, n, ns, ns);
  }
  if (p.spheres) {
    const M is = M::from_bits(p.spheres);
    V c3[3], n[3], x[3];
    lanes::load3(p.center, c3);
    for (int c = 0; c < 3; ++c) n[c] = q[c] - c3[c];
    lanes::normalize(n, p.spheres);
    const V r = V::load(p.radius);
    for (int c = 0; c < 3; ++c) x[c] = c3[c] + n[c] * r;
    lanes::select3(is, x, pos, pos);
    lanes::select3(is, n, ng, ng);
    lanes::select3(is, n, ns, ns);
  }
  if (p.triangles) {
    const M is = M::from_bits(p.triangles);
    V a[3], b[3], c3[3], n[3], x[3];
    lanes::load3(p.v0, a);
    lanes::load3(p.v1, b);
    lanes::load3(p.v2, c3);
    for (int c = 0; c < 3; ++c) x[c] = (a[c] + u * (b[c] - a[c])) + v * (c3[c] - a[c]);
    lanes::load3(p.tri_n, n);
    lanes::normalize(n, p.triangles);
    lanes::select3(is, x, pos, pos);
    lanes::select3(is, n, ng, ng);
    if (sc.accel.tri_normals.empty()) {
      lanes::select3(is, n, ns, ns);
    } else {
      V m0[3], m1[3], m2[3], s[3];
      lanes::load3(p.n0, m0);
      lanes::load3(p.n1, m1);
      lanes::load3(p.n2, m2);
      const V w = (V::broadcast(1.0f) - u) - v;
      for (int c = 0; c < 3; ++c) s[c] = (w * m0[c] + u * m1[c]) + v * m2[c];
      lanes::normalize(s, p.triangles);
      lanes::select3(is, s, ns, ns);
    }
  }
  // Facing the ray: both normals flipped where it hit the back (their w becomes -0), and an
  // interpolated normal that faces away replaced by the geometric one.
  const M entering = dot_dpps(dir, ng, zero) < zero;
  for (int c = 0; c < 3; ++c) {
    ng[c] = select(entering, ng[c], negate(ng[c]));
    ns[c] = select(entering, ns[c], negate(ns[c]));
  }
  const V ns_w_dir_w = select(entering, zero, V::broadcast(-0.0f));  // ns.w x dir.w (+0)
  const M facing = dot_dpps(ns, dir, ns_w_dir_w) < zero;
  for (int c = 0; c < 3; ++c) ns[c] = select(facing, ns[c], ng[c]);
  // Where secondary rays start (offset.h), per lane.
  V above[3];
  for (int c = 0; c < 3; ++c) above[c] = offset_coordinate(pos[c], ng[c], sc.offset_scale);
  lanes::store3(above, p.above);
  // The materials' values, material by material (a pass's hits share a few).
  V ka[3], kd[3], ks[3], kr = zero;
  for (int c = 0; c < 3; ++c) ka[c] = kd[c] = ks[c] = zero;
  {
    for (unsigned left = active; left;) {
      const std::uint32_t mi = p.material_index[std::countr_zero(left)];
      const Material& m = sc.materials[mi];
      unsigned same = p.one_material ? left : 0u;
      for (unsigned k = left; k && !p.one_material; k &= k - 1)
        same |= unsigned(p.material_index[std::countr_zero(k)] == mi) << std::countr_zero(k);
      const M is = M::from_bits(same);
      left &= ~same;
      for (int c = 0; c < 3; ++c) {
        ka[c] = select(is, V::broadcast(m.ambient[c]), ka[c]);
        kd[c] = select(is, V::broadcast(m.diffuse[c]), kd[c]);
        ks[c] = select(is, V::broadcast(m.specular[c]), ks[c]);
      }
      kr = select(is, V::broadcast(m.reflectivity), kr);
      if (m.checker_scale > 0.0f) {
        // Kd: the checker's colour in its odd cells of the world-space point
        const V inv = V::broadcast(1.0f / m.checker_scale);
        V parity = zero;
        for (int c = 0; c < 3; ++c)
          parity = parity + lanes::cell_parity((pos[c] + V::broadcast(sc.origin[c])) * inv);
        const M odd = is & (lanes::cell_parity(parity) > zero);
        for (int c = 0; c < 3; ++c) kd[c] = select(odd, V::broadcast(m.diffuse2[c]), kd[c]);
      }
    }
  }
  // Ka I_amb, weighted
  {
    V out[3];
    for (int c = 0; c < 3; ++c) out[c] = weight[c] * (ka[c] * V::broadcast(sc.ambient[c]));
    lanes::store3(out, p.ambient_term);
  }
  // Each light's term: the shadow ray's direction, length and weight (phong_lights).
  const std::size_t light_count = sc.lights.size();
  if (light_count > 0) {
    const M shiny_material = (ks[0] > zero) | (ks[1] > zero) | (ks[2] > zero);
    V view[3];
    for (int c = 0; c < 3; ++c) view[c] = negate(dir[c]);
    for (std::size_t k = 0; k < light_count; ++k) {
      const Light& light = sc.lights[k];
      PhongLanes::LightLanes& out = p.light[k];
      V to[3], l[3];
      for (int c = 0; c < 3; ++c) to[c] = V::broadcast(light.position[c]) - above[c];
      const V dist = sqrt(dot_dpps(to, to, zero));
      const V range = V::broadcast(light.range);
      const M in_range = dist < range;
      out.in_range = mlib::bits(in_range) & active;
      for (int c = 0; c < 3; ++c) l[c] = to[c] / dist;
      const V l_w = zero / dist;  // L's w: NaN where d is 0 or NaN
      const V l_w_n_w = l_w * zero;
      const V n_dot_l = dot_dpps(ns, l, l_w_n_w);
      const M lit = in_range & (dot_dpps(l, ng, l_w_n_w) > zero) & (n_dot_l > zero);
      out.lit = mlib::bits(lit) & active;
      if (!out.lit) continue;
      V term[3], r[3];
      for (int c = 0; c < 3; ++c) term[c] = kd[c] * n_dot_l;
      const V twice = V::broadcast(2.0f) * n_dot_l;
      for (int c = 0; c < 3; ++c) r[c] = twice * ns[c] - l[c];
      const V r_dot_v = dot_dpps(r, view, zero);
      const M shiny = lit & shiny_material & (r_dot_v > zero);
      if (const unsigned bits = mlib::bits(shiny) & active) {
        alignas(64) float base[kHitLanes], power[kHitLanes] = {};
        r_dot_v.store(base);
        for (unsigned m = bits; m; m &= m - 1) {
          const int j = std::countr_zero(m);
          power[j] = std::pow(base[j], sc.materials[p.material_index[j]].shininess);
        }
        const V pw = V::load(power);
        for (int c = 0; c < 3; ++c) term[c] = select(shiny, term[c] + ks[c] * pw, term[c]);
      }
      V weighted[3];
      const vec4 radiance = light.radiance();
      if (light.has_range()) {
        const V x = dist / range, x2 = x * x, w = V::broadcast(1.0f) - x2 * x2;
        const V window = w * w;
        for (int c = 0; c < 3; ++c)
          weighted[c] = weight[c] * (term[c] * (V::broadcast(radiance[c]) * window));
      } else {
        for (int c = 0; c < 3; ++c) weighted[c] = weight[c] * (term[c] * V::broadcast(radiance[c]));
      }
      lanes::store3(weighted, out.term);
      lanes::store3(l, out.dir);
      l_w.store(out.dir_w);
      dist.store(out.distance);
    }
  }
  // The reflected ray (phong_spawn), where deep and heavy enough.
  p.reflects = 0;
  if (depth < st.depth) {
    V w[3];
    for (int c = 0; c < 3; ++c) w[c] = weight[c] * kr;
    const M heavy = max(max(w[0], w[1]), w[2]) > V::broadcast(st.min_weight);  // hmax3
    p.reflects = mlib::bits((kr > zero) & heavy) & active;
    if (p.reflects) {
      // reflect(dir, ns) = dir - 2 ns (ns·dir)
      const V d = dot_dpps(ns, dir, ns_w_dir_w);
      V r[3];
      for (int c = 0; c < 3; ++c) r[c] = dir[c] - (V::broadcast(2.0f) * ns[c]) * d;
      lanes::store3(r, p.reflect_dir);
      (zero - zero * d).store(p.reflect_dir_w);  // 0 - (2 ns.w) d: +0, or NaN
      lanes::store3(w, p.reflect_weight);
    }
  }
}

// What a pass over the lanes of `active` adds to the counters (phong_lights and phong_spawn
// count each hit as they go; the lanes count a pass at once).
inline void count_lanes(const CompiledScene& sc, const PhongLanes& p, unsigned active,
                        RayCounts& counts) {
  const unsigned n = static_cast<unsigned>(std::popcount(active));
  counts.lights.points += n;
  counts.lights.in_lanes += n;
  counts.lights.considered += std::uint64_t(n) * sc.lights.size();
  for (std::size_t k = 0; k < sc.lights.size(); ++k) {
    counts.lights.in_range += static_cast<unsigned>(std::popcount(p.light[k].in_range));
    counts.shadow += static_cast<unsigned>(std::popcount(p.light[k].lit));
  }
  counts.reflection += static_cast<unsigned>(std::popcount(p.reflects));
}

// Lane l's results into the batch, as phong_lights and phong_spawn add them for one hit
// (`sample`: its ray's).
inline void emit_lane(const CompiledScene& sc, const PhongLanes& p, int l, std::uint32_t sample,
                      Batches& b) {
  const unsigned bit = 1u << l;
  b.colors[sample] += p.ambient(l);
  const std::size_t light_count = sc.lights.size();
  const vec4 above(p.above[0][l], p.above[1][l], p.above[2][l]);
  for (std::size_t k = 0; k < light_count; ++k) {
    const PhongLanes::LightLanes& lt = p.light[k];
    if (!(lt.lit & bit)) continue;
    b.shadows.push(above, vec4(lt.dir[0][l], lt.dir[1][l], lt.dir[2][l], lt.dir_w[l]),
                   lt.distance[l], vec4(lt.term[0][l], lt.term[1][l], lt.term[2][l]),
                   static_cast<std::uint32_t>(k), sample, false);
  }
  if (p.reflects & bit)
    b.next.push(above,
                vec4(p.reflect_dir[0][l], p.reflect_dir[1][l], p.reflect_dir[2][l],
                     p.reflect_dir_w[l]),
                vec4(p.reflect_weight[0][l], p.reflect_weight[1][l], p.reflect_weight[2][l]),
                sample);
}

// Every lane's shadow and reflected rays appended at once, a vector per column, the lanes
// that have one moved together (mlib::compress) in lane order, light after light: what
// emit_lane appends lane after lane, when the pass's other rays append nothing (misses),
// up to the order of a ray's shadow rays among other rays' when there are several lights.
// That order does not show when no two rays of the pass share a sample (the caller's to
// check): the batch is traced grouped by light, each light's rays in batch order, which
// is the same either way, and each sample's terms are summed in the order of its lights
// either way. `samples`: the rays' sample column at the pass's first ray. The ambient
// terms are the caller's to add.
inline void emit_lanes(const CompiledScene& sc, const PhongLanes& p, const std::uint32_t* samples,
                       Batches& b) {
  using lanes::V;
  const V sample = V::loadu(samples), zero = V::broadcast(0.0f);
  // n of the lanes of `mask` from `from` (kHitLanes floats) into column c of `to` at `at`.
  const auto append = [](auto& to, std::size_t at, int c, V from, unsigned mask) {
    compress(from, mask).storeu(to.f(c) + at);
  };
  const auto append3 = [&](auto& to, std::size_t at, int c, const float (&from)[3][kHitLanes],
                           unsigned mask) {
    for (int k = 0; k < 3; ++k) append(to, at, c + k, V::load(from[k]), mask);
  };
  for (std::size_t k = 0; k < sc.lights.size(); ++k) {
    const PhongLanes::LightLanes& lt = p.light[k];
    if (!lt.lit) continue;
    const unsigned n = static_cast<unsigned>(std::popcount(lt.lit));
    auto& to = b.shadows.columns();
    to.reserve(to.size() + kHitLanes);
    const std::size_t at = b.shadows.extend(static_cast<std::uint32_t>(k), n, false);
    append3(to, at, ShadowRays::kOrg, p.above, lt.lit);
    zero.storeu(to.f(ShadowRays::kOrg + 3) + at);
    append3(to, at, ShadowRays::kDir, lt.dir, lt.lit);
    append(to, at, ShadowRays::kDir + 3, V::load(lt.dir_w), lt.lit);
    append3(to, at, ShadowRays::kTerm, lt.term, lt.lit);
    append(to, at, ShadowRays::kDistance, V::load(lt.distance), lt.lit);
    append(to, at, ShadowRays::kSample, sample, lt.lit);
    const std::uint32_t light = static_cast<std::uint32_t>(k);
    V::broadcast(std::bit_cast<float>(light)).storeu(to.u(ShadowRays::kLight) + at);
    zero.storeu(to.u(ShadowRays::kUnoccluded) + at);  // traced
  }
  if (p.reflects) {
    const unsigned n = static_cast<unsigned>(std::popcount(p.reflects));
    auto& to = b.next.columns();
    to.reserve(to.size() + kHitLanes);
    const std::size_t at = to.extend(n);
    append3(to, at, PathRays::kOrg, p.above, p.reflects);
    zero.storeu(to.f(PathRays::kOrg + 3) + at);
    append3(to, at, PathRays::kDir, p.reflect_dir, p.reflects);
    append(to, at, PathRays::kDir + 3, V::load(p.reflect_dir_w), p.reflects);
    append3(to, at, PathRays::kWeight, p.reflect_weight, p.reflects);
    append(to, at, PathRays::kSample, sample, p.reflects);
  }
}

}  // namespace rt2::RT2_ISA
