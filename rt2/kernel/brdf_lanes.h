// rt2/kernel/brdf_lanes.h — brdf.h's physically based BRDF for kHitLanes light directions
// or surfaces at once: GGX, Smith, Schlick and the energy-conserving diffuse, with the
// split-sum table (brdf_lut.h) read lane by lane. The shading lanes use it across hits
// (pbr_lanes.h) and across a point's lights (pbr.h).
//
// Invariant: every lane computes what brdf.h computes, bit for bit (hit_lanes.h).
#pragma once

#include <algorithm>
#include <numbers>

#include "rt2/kernel/kernel.h"

#include "rt2/kernel/hit_lanes.h"
#include "rt2/shading/brdf_lut.h"

namespace rt2::RT2_ISA::lanes {


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

// The surfaces brdf_cos reads (brdf.h's PbrSurface as columns) and E(v) of each lane.
struct BrdfColumns {
  V f0[3], diffuse_scale[3], e_v[3], alpha, roughness;
};

// brdf(s, n, v, l, e_v) n·l (brdf.h) of each lane of `lit` (n·l > 0 there), the vectors'
// w lanes n_w, v_w and l_w as the vec4 code carries them, n·v and n·l as dot(n, v) and
// dot(n, l) give them; into term (x y z).
MLIB_INLINE void brdf_cos(const SplitSumTable& t, const BrdfColumns& s, const V* n, V n_w,
                          const V* v, V v_w, const V* l, V l_w, V n_dot_v, V n_dot_l,
                          unsigned lit, V* term) {
  const auto k = [](float c) { return V::broadcast(c); };
  const V zero = k(0.0f), one = k(1.0f);
  V h[3], h_w = v_w + l_w;
  for (int c = 0; c < 3; ++c) h[c] = v[c] + l[c];
  normalize(h, h_w, lit);
  const V n_dot_h = dot_dpps(n, h, n_w * h_w);
  V n_x_h[3];
  n_x_h[0] = n[1] * h[2] - n[2] * h[1];
  n_x_h[1] = n[2] * h[0] - n[0] * h[2];
  n_x_h[2] = n[0] * h[1] - n[1] * h[0];
  const V n_x_h_w = n_w * h_w - n_w * h_w;
  const V sin2_h = dot_dpps(n_x_h, n_x_h, n_x_h_w * n_x_h_w);
  const V h_dot_v = k(0.5f) * (dot_dpps(h, v, h_w * v_w) + dot_dpps(h, l, h_w * l_w));
  const V fc = schlick_weight(h_dot_v);
  // ggx_d
  const V a2 = s.alpha * s.alpha;
  const V kk = sin2_h + n_dot_h * n_dot_h * a2;
  const V d = select(n_dot_h <= zero, zero, a2 / (k(std::numbers::pi_v<float>) * kk * kk));
  // smith_visibility
  const V g_v = n_dot_l * sqrt(n_dot_v * n_dot_v * (one - a2) + a2);
  const V g_l = n_dot_v * sqrt(n_dot_l * n_dot_l * (one - a2) + a2);
  const V denom = g_v + g_l;
  const V vis = select(denom > zero, k(0.5f) / denom, zero);
  const V dv = d * vis;
  V a, b;
  split_sum(t, n_dot_l, s.roughness, a, b);
  const auto faces = n_dot_v > zero;  // brdf is 0 unless n·v > 0 (and n·l > 0)
  for (int c = 0; c < 3; ++c) {
    const V f = s.f0[c] + (one - s.f0[c]) * fc;
    const V e_l = s.f0[c] * a + b;
    const V brdf = s.diffuse_scale[c] * (one - s.e_v[c]) * (one - e_l) + f * dv;
    term[c] = select(faces, brdf, zero) * n_dot_l;
  }
}

}  // namespace rt2::RT2_ISA::lanes
