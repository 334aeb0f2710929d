// rt2/kernel/pbr_lanes.h — physically based shading (pbr.h) of up to kHitLanes hits in one
// SIMD pass (hit_lanes.h): emission and the environment's light (its spherical harmonics,
// the split-sum table, the prefiltered map), each light's BRDF term (shading/brdf.h: GGX,
// Smith, Schlick and the energy-conserving diffuse) and the mirror rays of smooth surfaces.
//
// Invariant: every lane computes what pbr.h computes for one hit, bit for bit (hit_lanes.h):
// the split-sum table and the prefiltered maps read per lane at the coordinates the lanes
// compute. Which hits:
// physically based without texture or transmission (CompiledScene::plain_pbr).
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <numbers>

#include "rt2/kernel/kernel.h"

#include "rt2/kernel/environment_lanes.h"
#include "rt2/kernel/hit_lanes.h"
#include "rt2/kernel/pbr.h"  // kMirrorRoughness
#include "rt2/shading/brdf.h"
#include "rt2/shading/environment.h"

namespace rt2::RT2_ISA {

namespace lanes {

// brdf_lut.cpp's clamp01: x > 0 ? (x < 1 ? x : 1) : 0.
MLIB_INLINE V clamp01(V x) {
  return select(x > V::broadcast(0.0f), select(x < V::broadcast(1.0f), x, V::broadcast(1.0f)),
                V::broadcast(0.0f));
}

// split_sum(mu, roughness) of each lane (brdf_lut.h), the table read lane by lane.
MLIB_INLINE void split_sum(const SplitSumTable& t, V mu, V roughness, V& a, V& b) {
  constexpr int kMu = SplitSumTable::kMu, kRows = SplitSumTable::kRoughness;
  const V x = clamp_std(sqrt(clamp01(mu)) * V::broadcast(float(kMu)) - V::broadcast(0.5f),
                        V::broadcast(0.0f), V::broadcast(float(kMu - 1)));
  const V y = clamp01(roughness) * V::broadcast(float(kRows - 1));
  alignas(64) float xs[kHitLanes], ys[kHitLanes], e[8][kHitLanes];
  x.store(xs);
  y.store(ys);
  for (int l = 0; l < kHitLanes; ++l) {
    const int i = std::min(int(xs[l]), kMu - 2), j = std::min(int(ys[l]), kRows - 2);
    xs[l] = float(i);
    ys[l] = float(j);
    const SplitSum* r0 = t.entry + std::size_t(j * kMu + i);
    const SplitSum* r1 = r0 + kMu;
    e[0][l] = r0[0].a, e[1][l] = r0[0].b, e[2][l] = r0[1].a, e[3][l] = r0[1].b;
    e[4][l] = r1[0].a, e[5][l] = r1[0].b, e[6][l] = r1[1].a, e[7][l] = r1[1].b;
  }
  const V tx = x - V::load(xs), ty = y - V::load(ys);
  const auto mix = [](V p, V q, V f) { return p + (q - p) * f; };
  const auto entry = [&](int k) { return V::load(e[k]); };
  a = mix(mix(entry(0), entry(2), tx), mix(entry(4), entry(6), tx), ty);
  b = mix(mix(entry(1), entry(3), tx), mix(entry(5), entry(7), tx), ty);
}

// (1 - clamp(cos, 0, 1))^5 (brdf.h's schlick_weight).
MLIB_INLINE V schlick_weight(V cos_theta) {
  const V m = V::broadcast(1.0f) - clamp_std(cos_theta, V::broadcast(0.0f), V::broadcast(1.0f));
  const V m2 = m * m;
  return m2 * m2 * m;
}

}  // namespace lanes

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
  // Each light's term brdf(l, v) n·l (brdf.h).
  light_lanes(sc, s, active, p, [&](const V* l, V n_dot_l, M lit, V* term) {
    V h[3];
    for (int c = 0; c < 3; ++c) h[c] = view[c] + l[c];  // w: -0 + +0
    lanes::normalize(h, mlib::bits(lit));
    const V n_dot_h = dot_dpps(n, h, s.ns_w_dir_w);  // n.w h.w = n.w (+0)
    V n_x_h[3];
    n_x_h[0] = n[1] * h[2] - n[2] * h[1];
    n_x_h[1] = n[2] * h[0] - n[0] * h[2];
    n_x_h[2] = n[0] * h[1] - n[1] * h[0];
    const V sin2_h = dot_dpps(n_x_h, n_x_h, zero);
    const V h_dot_v = k(0.5f) * (dot_dpps(h, view, k(-0.0f)) + dot_dpps(h, l, zero));
    const V fc = lanes::schlick_weight(h_dot_v);
    // ggx_d
    const V a2 = alpha * alpha;
    const V kk = sin2_h + n_dot_h * n_dot_h * a2;
    const V d = select(n_dot_h <= zero, zero, a2 / (k(std::numbers::pi_v<float>) * kk * kk));
    // smith_visibility
    const V g_v = n_dot_l * sqrt(n_dot_v * n_dot_v * (one - a2) + a2);
    const V g_l = n_dot_v * sqrt(n_dot_l * n_dot_l * (one - a2) + a2);
    const V denom = g_v + g_l;
    const V vis = select(denom > zero, k(0.5f) / denom, zero);
    const V dv = d * vis;
    V a, b;
    lanes::split_sum(table, n_dot_l, roughness, a, b);
    const M faces = n_dot_v > zero;  // n·l > 0 in every lit lane
    for (int c = 0; c < 3; ++c) {
      const V f = f0[c] + (one - f0[c]) * fc;
      const V e_l = f0[c] * a + b;
      const V brdf = diffuse_scale[c] * (one - e_v[c]) * (one - e_l) + f * dv;
      term[c] = select(faces, brdf, zero) * n_dot_l;
    }
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
