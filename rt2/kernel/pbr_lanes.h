// rt2/kernel/pbr_lanes.h — physically based shading (pbr.h) of up to kHitLanes hits in one
// SIMD pass (hit_lanes.h): emission and the environment's light (its spherical harmonics,
// the split-sum table, the prefiltered map), each light's BRDF term (shading/brdf.h: GGX,
// Smith, Schlick and the energy-conserving diffuse) and the mirror rays of smooth surfaces.
//
// Invariant: every lane computes what pbr.h computes for one hit, bit for bit (hit_lanes.h):
// the split-sum table and the prefiltered maps read per lane at the coordinates the lanes
// compute. Which hits: physically based without texture or transmission
// (CompiledScene::plain_pbr).
#pragma once

#include <cstdint>

#include "rt2/kernel/kernel.h"

#include "rt2/kernel/brdf_lanes.h"
#include "rt2/kernel/environment_lanes.h"
#include "rt2/kernel/hit_lanes.h"
#include "rt2/kernel/pbr.h"  // kMirrorRoughness
#include "rt2/shading/brdf.h"
#include "rt2/shading/environment.h"

namespace rt2::RT2_ISA {

// The physically based pass over the lanes of `active` (filled by gather_lanes) for rays
// first ... first + kHitLanes - 1 of `rays`: p's results, for a scene whose every hit
// considers all of its sc.lights.size() <= kMaxLaneLights lights (pbr_lights, pbr_spawn).
inline void shade_pbr_lanes(const CompiledScene& sc, const RenderSettings& st, int depth,
                            unsigned active, const PathRays& rays, std::size_t first,
                            HitLanes& p) {
  using lanes::V;
  using lanes::M;
  const auto k = [](float c) { return V::broadcast(c); };
  const V zero = k(0.0f), one = k(1.0f);
  SurfaceLanes s;
  surface_lanes(sc, rays, first, p, s);
  const auto& n = s.ns;  // pbr_point's normal: the shading normal
  // The materials' surfaces (CompiledScene::pbr_surfaces), material by material.
  V f0[3], diffuse[3], diffuse_scale[3], emissive[3], alpha = zero, roughness = zero,
      metallic = zero;
  for (int c = 0; c < 3; ++c) f0[c] = diffuse[c] = diffuse_scale[c] = emissive[c] = zero;
  each_material(p, active, [&](std::uint32_t mi, M is) {
    const PbrSurface& ps = sc.pbr_surfaces[mi];
    const Material& m = sc.materials[mi];
    for (int c = 0; c < 3; ++c) {
      f0[c] = select(is, k(ps.f0[c]), f0[c]);
      diffuse[c] = select(is, k(ps.diffuse[c]), diffuse[c]);
      diffuse_scale[c] = select(is, k(ps.diffuse_scale[c]), diffuse_scale[c]);
      emissive[c] = select(is, k(m.emissive[c]), emissive[c]);
    }
    alpha = select(is, k(ps.alpha), alpha);
    roughness = select(is, k(ps.roughness), roughness);
    metallic = select(is, k(ps.metallic), metallic);
  });
  const SplitSumTable& table = split_sum_table();
  // n·v, v = -dir (its w -dir.w: n.w v.w is -(n.w dir.w))
  V view[3];
  for (int c = 0; c < 3; ++c) view[c] = negate(s.dir[c]);
  const V n_dot_v = dot_dpps(n, view, negate(s.ns_w_dir_w));
  // Emission and the environment's light: E(v) of the lobe, the diffuse share kD.
  V e_v[3], kd[3], local[3], irradiance[3];
  {
    V a, b;
    lanes::split_sum(table, lanes::max_std(n_dot_v, k(1e-4f)), roughness, a, b);
    for (int c = 0; c < 3; ++c) e_v[c] = f0[c] * a + b;
  }
  for (int c = 0; c < 3; ++c) kd[c] = (one - e_v[c]) * (one - metallic);
  lanes::irradiance(sc.environment.irradiance_sh(), n, irradiance);
  for (int c = 0; c < 3; ++c) local[c] = emissive[c] + kd[c] * diffuse[c] * irradiance[c];
  // the prefiltered map around the mirror direction, where rough (or at the depth limit)
  const bool last = depth >= st.depth;
  if (const unsigned rough = active & (last ? ~0u : mlib::bits(roughness > k(kMirrorRoughness)))) {
    const V d = dot_dpps(n, s.dir, s.ns_w_dir_w);
    V r[3];
    for (int c = 0; c < 3; ++c) r[c] = s.dir[c] - (k(2.0f) * n[c]) * d;
    alignas(64) float us[kHitLanes], vs[kHitLanes], rs[kHitLanes];
    lanes::map_uv(sc.environment, r, us, vs);
    roughness.store(rs);
    V spec[3];
    lanes::specular(sc.environment, us, vs, rs, rough, spec);
    const M is = M::from_bits(rough);
    for (int c = 0; c < 3; ++c) local[c] = select(is, local[c] + spec[c] * e_v[c], local[c]);
  }
  {
    V out[3];
    for (int c = 0; c < 3; ++c) out[c] = s.weight[c] * local[c];
    lanes::store3(out, p.local_term);
  }
  // Each light's term brdf(l, v) n·l (brdf.h); n.w is +0 or -0 as the normal was flipped
  // (ns_w_dir_w, dir.w being +0), v.w = -0.
  lanes::BrdfColumns surface;
  for (int c = 0; c < 3; ++c)
    surface.f0[c] = f0[c], surface.diffuse_scale[c] = diffuse_scale[c], surface.e_v[c] = e_v[c];
  surface.alpha = alpha;
  surface.roughness = roughness;
  light_lanes(sc, s, active, p, [&](const V* l, V l_w, V n_dot_l, M lit, V* term) {
    lanes::brdf_cos(table, surface, n, s.ns_w_dir_w, view, k(-0.0f), l, l_w, n_dot_v, n_dot_l,
                    mlib::bits(lit), term);
  });
  // The mirror ray of a smooth surface (pbr_spawn), where deep and heavy enough.
  p.reflects = 0;
  if (!last) {
    const V fc = lanes::schlick_weight(lanes::max_std(n_dot_v, zero));
    V w[3];
    for (int c = 0; c < 3; ++c) w[c] = s.weight[c] * (f0[c] + (one - f0[c]) * fc);
    reflect_lanes(st, s, w, mlib::bits(roughness <= k(kMirrorRoughness)) & active, p);
  }
}

}  // namespace rt2::RT2_ISA
