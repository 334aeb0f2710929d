// rt2/kernel/phong.h — the thesis's Phong model (3.1, 3.2; SPEC "Shading") for one hit:
// I = Ka I_amb + sum over the lights that reach it [Kd I (L·N) + Ks I (R·V)^n] + Kr I_r +
// Kt I_t. phong_lanes.h computes the same for up to 16 hits in one SIMD pass, bit for bit.
#pragma once

#include <bit>
#include <cmath>

#include "rt2/kernel/kernel.h"

#include "rt2/kernel/batches.h"
#include "rt2/kernel/light_terms.h"
#include "rt2/kernel/secondary_rays.h"
#include "rt2/render/renderer.h"

namespace rt2::RT2_ISA {

// I_local = Ka I_amb into the sample now, and for each light of `lights` that reaches the
// surface the term Kd I (L·N) + Ks I (R·V)^n into the shadow batch (light_terms.h), with
// `in_lanes` kLightLanes lights at a time where the list is long enough (the same bits).
// `lights` holds every light in range, in scene order, whatever the culling.
MLIB_INLINE void phong_lights(const CompiledScene& sc, const PathRay& r, const SurfacePoint& s,
                              LightList lights, float pixel_angle, bool in_lanes, Batches& b,
                              RayCounts& counts) {
  const Material& m = sc.materials[s.material];
  const vec4 weight = r.weight();
  b.colors[r.sample] += weight * (m.ambient * sc.ambient);
  ++counts.lights.points;
  counts.lights.considered += lights.count;
  if (lights.count == 0) return;
  vec4 kd = m.diffuse_at(s.p + sc.origin);  // the checker lives in world coordinates
  if (m.base_color_texture != kNoTexture) {  // MTL's map_Kd
    const TexturePoint tp = texcoords_at(sc.accel, s, sc.origin);
    kd *= sc.textures.sample(m.base_color_texture, tp.u, tp.v,
                             s.t * pixel_angle * tp.per_world);
  }
  const vec4 view = -r.ray.dir;
  if (in_lanes && lights.count >= kMinLaneLights) {
    add_light_terms_lanes(sc, r, s, s.ns, lights, b, counts,
                          [&](const auto* l, auto l_w, auto n_dot_l, auto lit, auto* term) {
      using V = decltype(l_w);
      const auto k = [](float c) { return V::broadcast(c); };
      for (int c = 0; c < 3; ++c) term[c] = k(kd[c]) * n_dot_l;
      if (!m.has_specular()) return;
      // R = 2 (N·L) N - L, its w lane included
      const V twice = k(2.0f) * n_dot_l;
      V rr[3];
      for (int c = 0; c < 3; ++c) rr[c] = twice * k(s.ns[c]) - l[c];
      const V v[3] = {k(view[0]), k(view[1]), k(view[2])};
      const V r_dot_v = dot_dpps(rr, v, (twice * k(s.ns[3]) - l_w) * k(view[3]));
      const auto shiny = lit & (r_dot_v > k(0.0f));
      const unsigned bits = mlib::bits(shiny);
      if (!bits) return;
      alignas(64) float base[kLightLanes], power[kLightLanes] = {};
      r_dot_v.store(base);
      for (unsigned left = bits; left; left &= left - 1) {
        const int j = std::countr_zero(left);
        power[j] = std::pow(base[j], m.shininess);
      }
      const V pw = V::load(power);
      for (int c = 0; c < 3; ++c) term[c] = select(shiny, term[c] + k(m.specular[c]) * pw, term[c]);
    });
    return;
  }
  add_light_terms(sc, r, s, s.ns, lights, b, counts, [&](const vec4& l, float n_dot_l) -> vec4 {
    vec4 term = kd * n_dot_l;
    if (m.has_specular()) {
      const float r_dot_v = dot(2.0f * n_dot_l * s.ns - l, view);  // R = reflect(-L, N)
      if (r_dot_v > 0.0f) term += m.specular * std::pow(r_dot_v, m.shininess);
    }
    return term;
  });
}

// The secondary rays: refraction, Kt (or, on total internal reflection, its share
// reflected) and reflection, Kr, when deep and heavy enough.
inline void phong_spawn(const CompiledScene& sc, const RenderSettings& st, int depth,
                        const PathRay& r, const SurfacePoint& s, Batches& b, RayCounts& counts) {
  if (depth >= st.depth) return;
  const Material& m = sc.materials[s.material];
  if (m.transparency > 0.0f)
    push_refracted(sc, r, s, s.ns, m.ior, r.weight() * m.transparency, st.min_weight, b, counts);
  if (m.reflectivity > 0.0f)
    push_reflected(r, s, s.ns, r.weight() * m.reflectivity, st.min_weight, b, counts);
}


// A Phong hit: its light now and in the shadow batch, and its secondary rays.
MLIB_INLINE void shade_phong(const CompiledScene& sc, const RenderSettings& st, int depth,
                             const PathRay& r, const SurfacePoint& s, LightList lights,
                             float pixel_angle, Batches& b, RayCounts& counts) {
  phong_lights(sc, r, s, lights, pixel_angle, st.shading_lanes, b, counts);
  phong_spawn(sc, st, depth, r, s, b, counts);
}

}  // namespace rt2::RT2_ISA
