// rt2/kernel/light_terms.h — the lights of one shaded hit, whatever its material model: for
// each light of its list in range that faces the surface, the model's unshadowed term into
// the shadow batch, scaled there by what passes (shadows.h). A model gives its term per unit
// radiance for the unit direction l to the light and n·l (thesis 3.2; SPEC "Shading").
// add_light_terms_lanes does the same for kLightLanes lights of the list at a time, the
// range and facing tests as masks and the model's term in SIMD, bit for bit.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "rt2/kernel/kernel.h"

#include "mlib/vfloat.h"
#include "rt2/kernel/batches.h"
#include "rt2/kernel/plane_sphere_packet_intersect.h"  // dot_dpps
#include "rt2/render/compiled_scene.h"
#include "rt2/render/ray_counts.h"

namespace rt2::RT2_ISA {

// Appends a shadow ray from `origin` towards `light` (index li), unit direction l, `dist`
// away, carrying weight x (term x the light's radiance and range window), `term` being the
// unshadowed contribution per unit radiance.
MLIB_INLINE void push_shadow_ray(Batches& b, const vec4& origin, const vec4& l, float dist,
                                 const vec4& weight, const vec4& term, const Light& light,
                                 std::uint32_t li, std::uint32_t sample, bool unoccluded) {
  b.shadows.push(origin, l, dist,
                 weight * (term * (light.has_range() ? light.radiance() * range_window(light, dist)
                                                     : light.radiance())),
                 li, sample, unoccluded);
}

// For each light of `lights` within its range of s.above, in front of the surface (its
// geometric normal) and of the shading normal n: term(l, n·l) into the shadow batch, from
// s.above, weighted by the ray's weight. A light at the point itself (l NaN) adds nothing.
template <class Term>
MLIB_INLINE void add_light_terms(const CompiledScene& sc, const PathRay& r, const SurfacePoint& s,
                                 const vec4& n, LightList lights, Batches& b, RayCounts& counts,
                                 Term&& term) {
  const vec4& origin = s.above;
  for (std::size_t k = 0; k < lights.count; ++k) {
    const std::uint32_t li = lights[k];
    const Light& light = sc.lights[li];
    const vec4 to = light.position - origin;
    const float dist = std::sqrt(float(dot(to, to)));
    if (!in_range(light, dist)) continue;  // contributes exactly 0
    ++counts.lights.in_range;
    const vec4 l = to / dist;
    if (!(dot(l, s.ng) > 0.0f)) continue;  // the light is behind the surface (or at p)
    const float n_dot_l = dot(n, l);
    if (!(n_dot_l > 0.0f)) continue;
    const bool unoccluded = lights.sees && lights.sees[k];
    ++(unoccluded ? counts.lights.unoccluded : counts.shadow);
    push_shadow_ray(b, origin, l, dist, r.weight(), term(l, n_dot_l), light, li, r.sample,
                    unoccluded);
  }
}

// Lights per pass of add_light_terms_lanes, and the lists from which it pays.
inline constexpr int kLightLanes = mlib::kWidestLanes;
inline constexpr std::size_t kMinLaneLights = 4;

// add_light_terms over the lights of `lights`, kLightLanes at a time: each light's
// direction, distance and tests in SIMD (its w lanes as the vec4 code carries them), then
// term(l, l_w, n_dot_l, lit, t) for the model's term per unit radiance of every lit lane
// into t (x y z), and each lit light's shadow ray pushed in list order. The same rays,
// terms and counts as add_light_terms.
template <class TermLanes>
inline void add_light_terms_lanes(const CompiledScene& sc, const PathRay& r, const SurfacePoint& s,
                                  const vec4& n, LightList lights, Batches& b, RayCounts& counts,
                                  TermLanes&& term) {
  using V = mlib::vfloat<kLightLanes>;
  using M = typename V::bool_type;
  const vec4& origin = s.above;
  const auto k = [](float c) { return V::broadcast(c); };
  const V ng[3] = {k(s.ng[0]), k(s.ng[1]), k(s.ng[2])}, nv[3] = {k(n[0]), k(n[1]), k(n[2])};
  counts.lights.light_lanes += lights.count;
  for (std::size_t first = 0; first < lights.count; first += kLightLanes) {
    const int m = int(std::min<std::size_t>(kLightLanes, lights.count - first));
    // the lights' positions and ranges; lanes past the list out of range
    alignas(64) float pos[4][kLightLanes] = {}, range[kLightLanes] = {};
    for (int j = 0; j < m; ++j) {
      const Light& light = sc.lights[lights[first + std::size_t(j)]];
      for (int c = 0; c < 4; ++c) pos[c][j] = light.position[c];
      range[j] = light.range;
    }
    V to[3];
    for (int c = 0; c < 3; ++c) to[c] = V::load(pos[c]) - k(origin[c]);
    const V to_w = V::load(pos[3]) - k(origin[3]);
    const V dist = sqrt(dot_dpps(to, to, to_w * to_w));
    const M in_range = dist < V::load(range);
    const unsigned in = mlib::bits(in_range) & ((1u << m) - 1u);
    counts.lights.in_range += unsigned(std::popcount(in));
    if (!in) continue;
    V l[3];
    for (int c = 0; c < 3; ++c) l[c] = to[c] / dist;
    const V l_w = to_w / dist;
    const V n_dot_l = dot_dpps(nv, l, k(n[3]) * l_w);
    const M lit_mask = in_range & (dot_dpps(l, ng, l_w * k(s.ng[3])) > k(0.0f)) & (n_dot_l > k(0.0f));
    const unsigned lit = mlib::bits(lit_mask) & in;
    if (!lit) continue;
    V t[3];
    term(l, l_w, n_dot_l, lit_mask, t);
    alignas(64) float ls[4][kLightLanes], ts[3][kLightLanes], ds[kLightLanes];
    for (int c = 0; c < 3; ++c) l[c].store(ls[c]), t[c].store(ts[c]);
    l_w.store(ls[3]);
    dist.store(ds);
    for (unsigned left = lit; left; left &= left - 1) {
      const int j = std::countr_zero(left);
      const std::size_t at = first + std::size_t(j);
      const std::uint32_t li = lights[at];
      const bool unoccluded = lights.sees && lights.sees[at];
      ++(unoccluded ? counts.lights.unoccluded : counts.shadow);
      push_shadow_ray(b, origin, vec4(ls[0][j], ls[1][j], ls[2][j], ls[3][j]), ds[j], r.weight(),
                      vec4(ts[0][j], ts[1][j], ts[2][j]), sc.lights[li], li, r.sample, unoccluded);
    }
  }
}

}  // namespace rt2::RT2_ISA
