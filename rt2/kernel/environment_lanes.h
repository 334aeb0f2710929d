// rt2/kernel/environment_lanes.h — the environment's lookups (shading/environment.h) for
// kHitLanes directions at once: their map coordinates (equirect.h's direction_to_uv, with
// its polynomial atan2 and acos), the bilinear lookups of the source and the prefiltered
// maps (the texels loaded lane by lane, the rest in SIMD) and the spherical-harmonic
// irradiance.
//
// Invariant: every lane computes what the one-direction code computes, bit for bit: the
// same operations in the same order (hit_lanes.h).
#pragma once

#include <algorithm>
#include <bit>
#include <numbers>

#include "rt2/kernel/kernel.h"

#include "rt2/kernel/hit_lanes.h"
#include "rt2/shading/environment.h"

namespace rt2::RT2_ISA::lanes {

// Environment::irradiance(n) of each lane: sh9(n) against the coefficients, summed in their
// order.
MLIB_INLINE void irradiance(const IrradianceSh& sh, const V* n, V* e) {
  const auto k = [](float c) { return V::broadcast(c); };
  const V x = n[0], y = n[1], z = n[2];
  const V basis[9] = {k(0.282095f),
                      k(0.488603f) * y,
                      k(0.488603f) * z,
                      k(0.488603f) * x,
                      k(1.092548f) * x * y,
                      k(1.092548f) * y * z,
                      k(0.315392f) * (k(3.0f) * z * z - k(1.0f)),
                      k(1.092548f) * x * z,
                      k(0.546274f) * (x * x - y * y)};
  for (int c = 0; c < 3; ++c) {
    e[c] = k(sh.c[0][c]) * basis[0];
    for (std::size_t i = 1; i < 9; ++i) e[c] = e[c] + k(sh.c[i][c]) * basis[i];
  }
}

// equirect.h's fast_atan2 and fast_acos, lane by lane.
MLIB_INLINE V fast_atan2(V y, V x) {
  constexpr float kPi = std::numbers::pi_v<float>;
  const auto k = [](float c) { return V::broadcast(c); };
  const V zero = k(0.0f);
  const V ax = abs(x), ay = abs(y);
  const V hi = max_std(ax, ay), lo = min_std(ax, ay);
  const V z = lo / hi, z2 = z * z;
  V a = z * (k(0.99997726f) + z2 * (k(-0.33262347f) + z2 * (k(0.19354346f) + z2 * (k(-0.11643287f) +
             z2 * (k(0.05265332f) + z2 * k(-0.01172120f))))));
  a = select(ay > ax, k(0.5f * kPi) - a, a);
  a = select(x < zero, k(kPi) - a, a);
  a = select(y < zero, negate(a), a);
  return select(hi > zero, a, zero);  // (0, 0): 0
}
MLIB_INLINE V fast_acos(V x) {
  constexpr float kPi = std::numbers::pi_v<float>;
  const auto k = [](float c) { return V::broadcast(c); };
  const V ax = min_std(abs(x), k(1.0f));
  const V r = sqrt(k(1.0f) - ax) *
              (k(1.5707963050f) + ax * (k(-0.2145988016f) + ax * (k(0.0889789874f) + ax * (k(-0.0501743046f) +
               ax * (k(0.0308918810f) + ax * (k(-0.0170881256f) + ax * (k(0.0066700901f) +
               ax * k(-0.0012624911f))))))));
  return select(x < k(0.0f), k(kPi) - r, r);
}

// Environment::map_uv(d) of each lane's direction d (x y z), into u and v (kHitLanes each).
MLIB_INLINE void map_uv(const Environment& env, const V* d, float* u, float* v) {
  constexpr float kInvPi = std::numbers::inv_pi_v<float>;
  const auto k = [](float c) { return V::broadcast(c); };
  ((k(0.5f) + fast_atan2(d[0], negate(d[2])) * k(0.5f * kInvPi)) + k(env.u_shift())).store(u);
  (fast_acos(clamp_std(d[1], k(-1.0f), k(1.0f))) * k(kInvPi)).store(v);
}

// EquirectMap::bilinear({u[l], v[l]}) of lane l's map *maps[l], for the lanes of `mask`,
// into out (x y z); every lane's map must be valid (it is read for its size).
MLIB_INLINE void bilinear(const EquirectMap* const* maps, const float* u, const float* v,
                          unsigned mask, V* out) {
  const auto k = [](float c) { return V::broadcast(c); };
  alignas(64) float ws[kHitLanes], hs[kHitLanes];
  for (int l = 0; l < kHitLanes; ++l) ws[l] = float(maps[l]->width), hs[l] = float(maps[l]->height);
  const V w = V::load(ws), h = V::load(hs), zero = k(0.0f);
  const V x = V::load(u) * w - k(0.5f);
  V y = min_std(V::load(v) * h - k(0.5f), h - k(1.0f));
  y = select(y >= zero, y, zero);  // also NaN
  const V fx = floor(x), fy = floor(y);
  const V tx = x - fx, ty = y - fy;
  // wrap: floor(x) modulo the width, NaN or rounding up to it giving 0
  V m = fx - w * floor(fx / w);
  m = select((m >= zero) & (m < w), m, zero);
  alignas(64) float ms[kHitLanes], fys[kHitLanes], texel[4][3][kHitLanes] = {};
  m.store(ms);
  fy.store(fys);
  for (unsigned left = mask; left; left &= left - 1) {
    const int l = std::countr_zero(left);
    const EquirectMap& map = *maps[l];
    const int x0 = int(ms[l]), x1 = x0 + 1 == map.width ? 0 : x0 + 1;
    const int y0 = int(fys[l]), y1 = std::min(y0 + 1, map.height - 1);
    const vec4* corner[4] = {&map.at(x0, y0), &map.at(x1, y0), &map.at(x0, y1), &map.at(x1, y1)};
    for (int q = 0; q < 4; ++q)
      for (int c = 0; c < 3; ++c) texel[q][c][l] = (*corner[q])[c];
  }
  for (int c = 0; c < 3; ++c) {
    const V a = V::load(texel[0][c]), b = V::load(texel[1][c]);
    const V d = V::load(texel[2][c]), e = V::load(texel[3][c]);
    const V top = a + (b - a) * tx, bottom = d + (e - d) * tx;
    out[c] = top + (bottom - top) * ty;
  }
}

// Environment::specular_at({u[l], v[l]}, roughness[l]) for the lanes of `mask` (their
// roughness a number, as Scene::validate ensures), into out.
MLIB_INLINE void specular(const Environment& env, const float* u, const float* v,
                          const float* roughness, unsigned mask, V* out) {
  constexpr int kLevels = Environment::kSpecularLevels;
  const EquirectMap* lo[kHitLanes];
  const EquirectMap* hi[kHitLanes];
  alignas(64) float f[kHitLanes];
  for (int l = 0; l < kHitLanes; ++l) {
    // lanes outside `mask` read level 0's size only
    const float x = mask >> l & 1 ? std::clamp(roughness[l], 0.0f, 1.0f) * float(kLevels - 1) : 0.0f;
    const int level = std::min(int(x), kLevels - 2);
    lo[l] = &env.specular_map(level);
    hi[l] = &env.specular_map(level + 1);
    f[l] = x - float(level);
  }
  V a[3], b[3];
  bilinear(lo, u, v, mask, a);
  bilinear(hi, u, v, mask, b);
  const V t = V::load(f);
  for (int c = 0; c < 3; ++c) out[c] = a[c] + (b[c] - a[c]) * t;
}

}  // namespace rt2::RT2_ISA::lanes
