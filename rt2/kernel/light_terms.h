// rt2/kernel/light_terms.h — the lights of one shaded hit, whatever its material model: for
// each light of its list in range that faces the surface, the model's unshadowed term into
// the shadow batch, scaled there by what passes (shadows.h). A model gives its term per unit
// radiance for the unit direction l to the light and n·l (thesis 3.2; SPEC "Shading").
#pragma once

#include <cmath>
#include <cstdint>

#include "rt2/kernel/kernel.h"

#include "rt2/kernel/batches.h"
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

}  // namespace rt2::RT2_ISA
