// rt2/kernel/hit_lanes.h — up to kHitLanes hits shaded in one SIMD pass, structure of
// arrays: what every material model's pass shares. gather_lanes fills the lanes with the
// hits a model takes, surface_lanes makes their surface points (surface_point.h),
// light_lanes each light's shadow ray, reflect_lanes the reflected rays; a model's pass
// (phong_lanes.h, pbr_lanes.h) adds its terms, and emit_lane / emit_lanes put every lane's
// results into the batches.
//
// Invariant: every lane computes what its model's one-hit code computes, bit for bit: the
// same operations in the same order, vec4's dot product as (x x' + y y') + (z z' + w w')
// with the w lanes the one-hit code carries, normalize's rescaling path per lane. Each
// lane's results are emitted in batch order (emit_lane, or emit_lanes where that order is
// kept), so the batches come out as the one-hit code makes them. Which hits: those on a
// material without texture or transparency, outside instances, when every hit considers
// every light and there are at most kMaxLaneLights lights.
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
struct HitLanes {
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
  alignas(64) F3 above, local_term, reflect_dir, reflect_weight;  // local_term: local(l)
  alignas(64) float reflect_dir_w[kHitLanes];
  unsigned reflects = 0;  // lanes that spawn a reflected ray
  struct LightLanes {
    alignas(64) F3 dir, term;
    alignas(64) F dir_w, distance;
    unsigned lit = 0, in_range = 0;
  };
  LightLanes light[kMaxLaneLights];

  // Lane l's light added to its sample now, weighted.
  MLIB_INLINE vec4 local(int l) const {
    return vec4(local_term[0][l], local_term[1][l], local_term[2][l]);
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
inline void gather_hits(const Batches& b, std::size_t first, std::size_t end, HitLanes& p) {
  namespace simd = mlib::simd;
  for (int j = 0; j < kHitLanes / 4; ++j) {
    const Hit* h[4];
    for (int k = 0; k < 4; ++k) h[k] = &b.hits[std::min(first + std::size_t(4 * j + k), end - 1)];
    lanes::put4(simd::load_xyz0(&h[0]->t), simd::load_xyz0(&h[1]->t), simd::load_xyz0(&h[2]->t),
                simd::load_xyz0(&h[3]->t), p.t, p.u, p.v, j);
  }
}

// Gathers the hits of rays [first, end) of the batch (at most kHitLanes) that take the
// lanes into p: those on a material m with takes[m] (CompiledScene::plain_phong or
// plain_pbr), outside instances; returns their lanes. Four lanes at a time (a transpose of
// four vec4s per quantity), or, when every ray hit one primitive, its data broadcast.
// Lanes past `end`, and the fields of other kinds, hold copies of a valid lane.
inline unsigned gather_lanes(const CompiledScene& sc, const std::uint8_t* takes, const Batches& b,
                             std::size_t first, std::size_t end, HitLanes& p) {
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
    if (!takes[material]) return 0;
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
    // A hit on a material of `takes` takes lane l; without branches on the material, whose
    // kinds mix in a batch.
    // (a hit in an instance is shaded one by one: surface_at places it in the world)
    const PrimRef prim = l < n && hits[l].instance == kNoInstance ? hits[l].prim : kNoHit;
    if (prim == kNoHit) continue;
    const std::uint32_t material = acc.material_of(prim);
    const unsigned bit = unsigned(takes[material]) << l;
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

// std::clamp(x, lo, hi), std::min(a, b) and std::max(a, b) as the standard defines them
// (x < lo ? lo : hi < x ? hi : x; b < a ? b : a; a < b ? b : a), NaN included.
MLIB_INLINE V clamp_std(V x, V lo, V hi) { return select(x < lo, lo, select(hi < x, hi, x)); }
MLIB_INLINE V min_std(V a, V b) { return select(b < a, b, a); }
MLIB_INLINE V max_std(V a, V b) { return select(a < b, b, a); }
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

// (a, w) / |(a, w)| as vec4's normalize, its w lane included, in the lanes of `mask`.
MLIB_INLINE void normalize(V* a, V& w, unsigned mask) {
  const V len2 = dot_dpps(a, a, w * w);
  const unsigned slow =
      mask & ~mlib::bits((len2 >= V::broadcast(FLT_MIN)) & (len2 <= V::broadcast(FLT_MAX)));
  alignas(64) float in[4][kHitLanes];
  if (slow)
    for (int c = 0; c < 4; ++c) (c < 3 ? a[c] : w).store(in[c]);
  const V len = sqrt(len2);
  for (int c = 0; c < 3; ++c) a[c] = a[c] / len;
  w = w / len;
  if (!slow) return;
  alignas(64) float out[4][kHitLanes];
  for (int c = 0; c < 4; ++c) (c < 3 ? a[c] : w).store(out[c]);
  for (unsigned m = slow; m; m &= m - 1) {
    const int l = std::countr_zero(m);
    const vec4 n = mlib::normalize(vec4(in[0][l], in[1][l], in[2][l], in[3][l]));
    for (int c = 0; c < 4; ++c) out[c][l] = n[c];
  }
  for (int c = 0; c < 3; ++c) a[c] = V::load(out[c]);
  w = V::load(out[3]);
}

}  // namespace lanes

// The surface points of a pass's lanes (surface_at, per kind, then chosen per lane), with
// their rays' directions and weights.
struct SurfaceLanes {
  using V = lanes::V;
  V dir[3], weight[3];  // the rays'
  V pos[3], ng[3], ns[3];  // surface_at's p, ng, ns, facing the ray
  V above[3];              // where secondary rays start (offset.h)
  V ns_w_dir_w;            // ns.w x dir.w (+0 or -0) for dot products with the direction
};

// The surface points of the lanes filled by gather_lanes, for rays first ... first +
// kHitLanes - 1 of `rays`; `above` also into p.
MLIB_INLINE void surface_lanes(const CompiledScene& sc, const PathRays& rays, std::size_t first,
                               HitLanes& p, SurfaceLanes& out) {
  using lanes::V;
  using lanes::M;
  const V zero = V::broadcast(0.0f);
  V org[3];
  auto& dir = out.dir;
  auto& pos = out.pos;
  auto& ng = out.ng;
  auto& ns = out.ns;
  const auto& columns = rays.columns();
  for (int c = 0; c < 3; ++c) {
    org[c] = V::loadu(columns.f(PathRays::kOrg + c) + first);
    dir[c] = V::loadu(columns.f(PathRays::kDir + c) + first);
    out.weight[c] = V::loadu(columns.f(PathRays::kWeight + c) + first);
  }
  const V t = V::load(p.t), u = V::load(p.u), v = V::load(p.v);
  // The surface point: p, ng, ns (surface_at) per kind, then chosen per lane.
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
  out.ns_w_dir_w = select(entering, zero, V::broadcast(-0.0f));  // ns.w x dir.w (+0)
  const M facing = dot_dpps(ns, dir, out.ns_w_dir_w) < zero;
  for (int c = 0; c < 3; ++c) ns[c] = select(facing, ns[c], ng[c]);
  // Where secondary rays start (offset.h), per lane.
  for (int c = 0; c < 3; ++c) out.above[c] = offset_coordinate(pos[c], ng[c], sc.offset_scale);
  lanes::store3(out.above, p.above);
}

// f(m, is) for each material m among the lanes of `active`, `is` the mask of its lanes (a
// pass's hits share a few).
template <class F>
MLIB_INLINE void each_material(const HitLanes& p, unsigned active, F&& f) {
  for (unsigned left = active; left;) {
    const std::uint32_t mi = p.material_index[std::countr_zero(left)];
    unsigned same = p.one_material ? left : 0u;
    for (unsigned k = left; k && !p.one_material; k &= k - 1)
      same |= unsigned(p.material_index[std::countr_zero(k)] == mi) << std::countr_zero(k);
    left &= ~same;
    f(mi, lanes::M::from_bits(same));
  }
}

// Each light's shadow ray from the lanes of `active` (light_terms.h's add_light_terms):
// its direction and length, the lanes in its range and those it lights (in range, in front
// of the geometric and the shading normal), and for those `term(l, l_w, n_dot_l, lit, t)`, the
// model's term per unit radiance into t, weighted here by the ray's weight and the light's
// radiance and range window; into p.light[k].
template <class Term>
MLIB_INLINE void light_lanes(const CompiledScene& sc, const SurfaceLanes& s, unsigned active,
                             HitLanes& p, Term&& term) {
  using lanes::V;
  using lanes::M;
  const V zero = V::broadcast(0.0f);
  for (std::size_t k = 0; k < sc.lights.size(); ++k) {
    const Light& light = sc.lights[k];
    HitLanes::LightLanes& out = p.light[k];
    V to[3], l[3];
    for (int c = 0; c < 3; ++c) to[c] = V::broadcast(light.position[c]) - s.above[c];
    const V dist = sqrt(dot_dpps(to, to, zero));
    const V range = V::broadcast(light.range);
    const M in_range = dist < range;
    out.in_range = mlib::bits(in_range) & active;
    for (int c = 0; c < 3; ++c) l[c] = to[c] / dist;
    const V l_w = zero / dist;  // L's w: NaN where d is 0 or NaN
    const V l_w_n_w = l_w * zero;
    const V n_dot_l = dot_dpps(s.ns, l, l_w_n_w);
    const M lit = in_range & (dot_dpps(l, s.ng, l_w_n_w) > zero) & (n_dot_l > zero);
    out.lit = mlib::bits(lit) & active;
    if (!out.lit) continue;
    V t[3], weighted[3];
    term(l, l_w, n_dot_l, lit, t);
    const vec4 radiance = light.radiance();
    if (light.has_range()) {
      const V x = dist / range, x2 = x * x, w = V::broadcast(1.0f) - x2 * x2;
      const V window = w * w;
      for (int c = 0; c < 3; ++c)
        weighted[c] = s.weight[c] * (t[c] * (V::broadcast(radiance[c]) * window));
    } else {
      for (int c = 0; c < 3; ++c) weighted[c] = s.weight[c] * (t[c] * V::broadcast(radiance[c]));
    }
    lanes::store3(weighted, out.term);
    lanes::store3(l, out.dir);
    l_w.store(out.dir_w);
    dist.store(out.distance);
  }
}

// The reflected rays (secondary_rays.h's push_reflected) of the lanes of `can`, of weights
// w: those heavy enough, into p (the caller clears p.reflects at the depth limit).
MLIB_INLINE void reflect_lanes(const RenderSettings& st, const SurfaceLanes& s,
                               const lanes::V* w, unsigned can, HitLanes& p) {
  using lanes::V;
  const V zero = V::broadcast(0.0f);
  const auto heavy = max(max(w[0], w[1]), w[2]) > V::broadcast(st.min_weight);  // hmax3
  p.reflects = mlib::bits(heavy) & can;
  if (!p.reflects) return;
  // reflect(dir, ns) = dir - 2 ns (ns·dir)
  const V d = dot_dpps(s.ns, s.dir, s.ns_w_dir_w);
  V r[3];
  for (int c = 0; c < 3; ++c) r[c] = s.dir[c] - (V::broadcast(2.0f) * s.ns[c]) * d;
  lanes::store3(r, p.reflect_dir);
  (zero - zero * d).store(p.reflect_dir_w);  // 0 - (2 ns.w) d: +0, or NaN
  lanes::store3(w, p.reflect_weight);
}

// What a pass over the lanes of `active` adds to the counters (the one-hit code counts
// each hit as it goes; the lanes count a pass at once).
inline void count_lanes(const CompiledScene& sc, const HitLanes& p, unsigned active,
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

// Lane l's results into the batch, as the one-hit code adds them (its light now, its
// shadow rays light by light, its reflected ray; `sample`: its ray's).
inline void emit_lane(const CompiledScene& sc, const HitLanes& p, int l, std::uint32_t sample,
                      Batches& b) {
  const unsigned bit = 1u << l;
  b.colors[sample] += p.local(l);
  const std::size_t light_count = sc.lights.size();
  const vec4 above(p.above[0][l], p.above[1][l], p.above[2][l]);
  for (std::size_t k = 0; k < light_count; ++k) {
    const HitLanes::LightLanes& lt = p.light[k];
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
// either way. `samples`: the rays' sample column at the pass's first ray. The local
// terms are the caller's to add.
inline void emit_lanes(const CompiledScene& sc, const HitLanes& p, const std::uint32_t* samples,
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
    const HitLanes::LightLanes& lt = p.light[k];
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
