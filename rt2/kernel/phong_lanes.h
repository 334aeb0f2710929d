// rt2/kernel/phong_lanes.h — Phong shading (phong.h) of up to kHitLanes hits in one SIMD
// pass (hit_lanes.h): the ambient term, each light's term and the reflected rays.
//
// Invariant: every lane computes what phong.h computes for one hit, bit for bit (hit_lanes.h),
// std::pow per lane. Which hits: Phong without texture or transparency
// (CompiledScene::plain_phong).
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>

#include "rt2/kernel/kernel.h"

#include "rt2/kernel/hit_lanes.h"

namespace rt2::RT2_ISA {

namespace lanes {

// The checker's cell parity of x (floor(x) as a 64-bit integer, & 1): 1 or 0.
MLIB_INLINE V cell_parity(V x) {
  const V f = floor(x);
  const V odd = f - V::broadcast(2.0f) * floor(V::broadcast(0.5f) * f);
  return select(abs(f) < V::broadcast(16777216.0f), odd, V::broadcast(0.0f));
}

}  // namespace lanes

// The Phong pass over the lanes of `active` (filled by gather_lanes) for rays first ...
// first + kHitLanes - 1 of `rays`: p's results, for a scene whose every hit considers all
// of its sc.lights.size() <= kMaxLaneLights lights.
inline void shade_phong_lanes(const CompiledScene& sc, const RenderSettings& st, int depth,
                              unsigned active, const PathRays& rays, std::size_t first,
                              HitLanes& p) {
  using lanes::V;
  using lanes::M;
  const V zero = V::broadcast(0.0f);
  SurfaceLanes s;
  surface_lanes(sc, rays, first, p, s);
  // The materials' values, material by material.
  V ka[3], kd[3], ks[3], kr = zero;
  for (int c = 0; c < 3; ++c) ka[c] = kd[c] = ks[c] = zero;
  each_material(p, active, [&](std::uint32_t mi, M is) {
    const Material& m = sc.materials[mi];
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
        parity = parity + lanes::cell_parity((s.pos[c] + V::broadcast(sc.origin[c])) * inv);
      const M odd = is & (lanes::cell_parity(parity) > zero);
      for (int c = 0; c < 3; ++c) kd[c] = select(odd, V::broadcast(m.diffuse2[c]), kd[c]);
    }
  });
  // Ka I_amb, weighted
  {
    V out[3];
    for (int c = 0; c < 3; ++c) out[c] = s.weight[c] * (ka[c] * V::broadcast(sc.ambient[c]));
    lanes::store3(out, p.local_term);
  }
  // Each light's term Kd (L·N) + Ks (R·V)^n (phong_lights).
  const M shiny_material = (ks[0] > zero) | (ks[1] > zero) | (ks[2] > zero);
  V view[3];
  for (int c = 0; c < 3; ++c) view[c] = negate(s.dir[c]);
  light_lanes(sc, s, active, p, [&](const V* l, V, V n_dot_l, M lit, V* term) {
    for (int c = 0; c < 3; ++c) term[c] = kd[c] * n_dot_l;
    const V twice = V::broadcast(2.0f) * n_dot_l;
    V r[3];
    for (int c = 0; c < 3; ++c) r[c] = twice * s.ns[c] - l[c];
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
  });
  // The reflected ray (phong_spawn), where deep and heavy enough.
  p.reflects = 0;
  if (depth < st.depth) {
    V w[3];
    for (int c = 0; c < 3; ++c) w[c] = s.weight[c] * kr;
    reflect_lanes(st, s, w, mlib::bits(kr > zero) & active, p);
  }
}

}  // namespace rt2::RT2_ISA
