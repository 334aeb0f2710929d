// rt2/kernel/pbr.h — physically based shading of one hit (Material::model == Shading::pbr):
// glTF 2.0's metallic-roughness model with the Cook-Torrance GGX BRDF of shading/brdf.h,
// reference/pbr-chapter.txt's pipeline on a ray tracer's hits. Textures are filtered over
// the pixel cone's footprint at the hit; emission, the environment's light (the split sum:
// the prefiltered map times the lobe's albedo, and 9 spherical harmonics for the diffuse
// part, with brdf.h's energy-conserving kD) and every light through the BRDF. A smooth
// surface (roughness <= kMirrorRoughness) reflects a mirror ray weighted by Schlick's
// Fresnel instead of the prefiltered map, so the Whitted recursion sees the scene in it; a
// transmissive one refracts (1 - F) transmission (1 - metallic) of its base colour
// (KHR_materials_transmission). Rough surfaces reflect the environment only.
#pragma once

#include <algorithm>
#include <cmath>

#include "rt2/kernel/kernel.h"

#include "rt2/geometry/optics.h"
#include "rt2/kernel/batches.h"
#include "rt2/kernel/brdf_lanes.h"
#include "rt2/kernel/light_terms.h"
#include "rt2/kernel/secondary_rays.h"
#include "rt2/render/renderer.h"
#include "rt2/shading/brdf.h"

namespace rt2::RT2_ISA {

// The roughness at or below which a surface is a mirror for the Whitted recursion.
inline constexpr float kMirrorRoughness = 0.05f;

// A physically based material's values at one surface point, textures applied.
struct PbrPoint {
  PbrSurface surface;  // brdf.h: diffuse colour (less what is transmitted), F0, alpha
  vec4 n;              // shading normal (normal-mapped), facing the viewer
  vec4 emissive;
  vec4 base;           // the base colour, which tints transmitted light
  float transmission;  // share of the non-reflected light refracted (0 for metals)
};

// A tangent-space normal map's normal at triangle hit `s`: texel (x, y, z) in [0, 1]
// stands for (2x - 1, 2y - 1, 2z - 1) in the frame of the tangent T = dP/du, the
// bitangent B = dP/dv (from the triangle's texture coordinates, made orthogonal to the
// shading normal N) and N; x and y scaled by `scale` (glTF's normalTexture.scale). A
// triangle whose texture coordinates are degenerate keeps N.
inline vec4 normal_mapped(const Accel& acc, const SurfacePoint& s, const vec4& texel,
                          float scale) {
  const std::uint32_t i = prim_index(s.prim);
  const Triangle tri = world_triangle(acc, i, s.instance);
  const auto& c = acc.tri_texcoords[i];
  const vec4 e1 = tri.v1 - tri.v0, e2 = tri.v2 - tri.v0;
  const float du1 = c[1][0] - c[0][0], dv1 = c[1][1] - c[0][1];
  const float du2 = c[2][0] - c[0][0], dv2 = c[2][1] - c[0][1];
  const float det = du1 * dv2 - du2 * dv1;
  if (!(std::fabs(det) > 0.0f)) return s.ns;
  const vec4 dpdu = (e1 * dv2 - e2 * dv1) / det;
  const vec4 dpdv = (e2 * du1 - e1 * du2) / det;
  const vec4 t = dpdu - s.ns * dot(s.ns, dpdu);
  const float tt = dot(t, t);
  if (!(tt > 0.0f) || !std::isfinite(tt)) return s.ns;
  const vec4 tu = t / std::sqrt(tt);
  // B's sign from the texture's handedness (a mirrored mapping flips it)
  const vec4 b = cross(s.ns, tu);
  const vec4 bt = dot(b, dpdv) < 0.0f ? vec4(-b) : b;
  const float x = (2.0f * float(texel[0]) - 1.0f) * scale;
  const float y = (2.0f * float(texel[1]) - 1.0f) * scale;
  const float z = 2.0f * float(texel[2]) - 1.0f;
  const vec4 n = tu * x + bt * y + s.ns * z;
  const float nn = dot(n, n);
  return nn > 0.0f && std::isfinite(nn) ? n / std::sqrt(nn) : s.ns;
}

// The material of `s` with its textures sampled over the pixel cone's width at the hit,
// s.t x pixel_angle (the ray's own length: for a secondary ray, an underestimate of its
// path's cone, so reflections sample textures a little sharp).
inline PbrPoint pbr_point(const CompiledScene& sc, const Material& m, const SurfacePoint& s,
                          const vec4& view, float pixel_angle) {
  if (m.base_color_texture == kNoTexture && m.metallic_roughness_texture == kNoTexture &&
      m.emissive_texture == kNoTexture && m.normal_texture == kNoTexture &&
      m.roughness_texture == kNoTexture && m.metallic_texture == kNoTexture)
    return PbrPoint{sc.pbr_surfaces[s.material], s.ns, m.emissive, m.base_color,
                    m.transmission * (1.0f - m.metallic)};
  vec4 base = m.base_color, emissive = m.emissive;
  float metallic = m.metallic, roughness = m.roughness;
  vec4 n = s.ns;
  const TexturePoint tp = texcoords_at(sc.accel, s, sc.origin);
  const float width = s.t * pixel_angle * tp.per_world;
  const auto sample = [&](std::uint32_t t) { return sc.textures.sample(t, tp.u, tp.v, width); };
  if (m.base_color_texture != kNoTexture) base *= sample(m.base_color_texture);
  if (m.emissive_texture != kNoTexture) emissive *= sample(m.emissive_texture);
  if (m.metallic_roughness_texture != kNoTexture) {
    const vec4 mr = sample(m.metallic_roughness_texture);
    roughness = std::clamp(roughness * float(mr[1]), 0.0f, 1.0f);
    metallic = std::clamp(metallic * float(mr[2]), 0.0f, 1.0f);
  }
  if (m.roughness_texture != kNoTexture)
    roughness = std::clamp(roughness * float(sample(m.roughness_texture)[0]), 0.0f, 1.0f);
  if (m.metallic_texture != kNoTexture)
    metallic = std::clamp(metallic * float(sample(m.metallic_texture)[0]), 0.0f, 1.0f);
  if (m.normal_texture != kNoTexture && prim_tag(s.prim) == kTriangleTag &&
      !sc.accel.tri_texcoords.empty()) {
    const vec4 mapped = normal_mapped(sc.accel, s, sample(m.normal_texture), m.normal_scale);
    if (dot(mapped, view) > 0.0f) n = mapped;  // a mapped normal facing away is ignored
  }
  return PbrPoint{pbr_surface(base, metallic, roughness, m.transmission), n, emissive, base,
                  m.transmission * (1.0f - metallic)};
}

// Emission and the light from far away into the sample's colour now, every light's BRDF
// term into the shadow batch (light_terms.h), with `in_lanes` kLightLanes lights at a time
// where the list is long enough (the same bits). `last` says that the ray is at the depth
// limit: a mirror then shows the prefiltered environment instead of the ray it cannot spawn
// (rather than nothing, as Phong's does).
inline void pbr_lights(const CompiledScene& sc, const PathRay& r, const SurfacePoint& s,
                       LightList lights, float pixel_angle, bool last, bool in_lanes,
                       Batches& b, RayCounts& counts, PbrPoint& out) {
  const Material& m = sc.materials[s.material];
  const vec4 view = -r.ray.dir;
  out = pbr_point(sc, m, s, view, pixel_angle);
  const PbrPoint& p = out;
  const float n_dot_v = std::max(float(dot(p.n, view)), 1e-4f);
  // emission and the light from far away: the lobe reflects E(v) of it (the split sum's
  // F0 A + B), the diffuse term what brdf.h's kD leaves, (1 - metallic)(1 - E(v))
  const vec4 e_v = specular_albedo(p.surface, n_dot_v);
  const vec4 kd = (vec4(1.0f, 1.0f, 1.0f) - e_v) * (1.0f - p.surface.metallic);
  vec4 local = p.emissive + kd * p.surface.diffuse * sc.environment.irradiance(p.n);
  if (p.surface.roughness > kMirrorRoughness || last)
    local += sc.environment.specular(reflect(r.ray.dir, p.n), p.surface.roughness) * e_v;
  const vec4 weight = r.weight();
  b.colors[r.sample] += weight * local;
  ++counts.lights.points;
  counts.lights.considered += lights.count;
  if (in_lanes && lights.count >= kMinLaneLights) {
    using V = lanes::V;
    const auto k = [](float c) { return V::broadcast(c); };
    lanes::BrdfColumns surface;
    for (int c = 0; c < 3; ++c) {
      surface.f0[c] = k(p.surface.f0[c]);
      surface.diffuse_scale[c] = k(p.surface.diffuse_scale[c]);
      surface.e_v[c] = k(e_v[c]);
    }
    surface.alpha = k(p.surface.alpha);
    surface.roughness = k(p.surface.roughness);
    const V n[3] = {k(p.n[0]), k(p.n[1]), k(p.n[2])}, v[3] = {k(view[0]), k(view[1]), k(view[2])};
    const V n_dot_v_raw = k(dot(p.n, view));  // brdf's n·v, not clamped
    add_light_terms_lanes(sc, r, s, p.n, lights, b, counts,
                          [&](const V* l, V l_w, V n_dot_l, V::bool_type lit, V* term) {
      lanes::brdf_cos(split_sum_table(), surface, n, k(p.n[3]), v, k(view[3]), l, l_w,
                      n_dot_v_raw, n_dot_l, mlib::bits(lit), term);
    });
    return;
  }
  add_light_terms(sc, r, s, p.n, lights, b, counts, [&](const vec4& l, float n_dot_l) -> vec4 {
    return brdf(p.surface, p.n, view, l, e_v) * n_dot_l;
  });
}

// The secondary rays: the mirror ray of a smooth surface and the refracted ray of a
// transmissive one.
inline void pbr_spawn(const CompiledScene& sc, const RenderSettings& st, int depth,
                      const PathRay& r, const SurfacePoint& s, const PbrPoint& p, Batches& b,
                      RayCounts& counts) {
  if (depth >= st.depth) return;
  const bool mirror = p.surface.roughness <= kMirrorRoughness;
  if (!mirror && !(p.transmission > 0.0f)) return;
  const vec4 view = -r.ray.dir;
  const float n_dot_v = std::max(float(dot(p.n, view)), 0.0f);
  const vec4 f = fresnel_schlick(n_dot_v, p.surface.f0);
  if (p.transmission > 0.0f)
    push_refracted(sc, r, s, p.n, sc.materials[s.material].ior,
                   r.weight() * (vec4(1.0f, 1.0f, 1.0f) - f) * p.base * p.transmission,
                   st.min_weight, b, counts);
  if (mirror) push_reflected(r, s, p.n, r.weight() * f, st.min_weight, b, counts);
}

// A physically based hit: its light now and in the shadow batch, and its secondary rays.
// Kept out of the kernel's loop over hits, which stays the Phong path's.
[[gnu::noinline]] inline void shade_pbr(const CompiledScene& sc, const RenderSettings& st,
                                        int depth, const PathRay& r, const SurfacePoint& s,
                                        LightList lights, float pixel_angle, Batches& b,
                                        RayCounts& counts) {
  PbrPoint p;
  pbr_lights(sc, r, s, lights, pixel_angle, depth >= st.depth, st.shading_lanes, b, counts, p);
  pbr_spawn(sc, st, depth, r, s, p, b, counts);
}

}  // namespace rt2::RT2_ISA
