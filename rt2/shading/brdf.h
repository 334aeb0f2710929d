// rt2/shading/brdf.h — the physically based BRDF of Shading::pbr: Cook-Torrance microfacet
// specular (GGX normal distribution, height-correlated Smith visibility, Schlick Fresnel)
// plus a Lambert diffuse, in glTF 2.0's metallic-roughness parametrisation:
//   f(l, v) = kD diffuse / pi + D(h) V(l, v) F(h·v),
//   kD = (1 - metallic) (1 - E(v)) (1 - E(l)) / (1 - E_avg)  (energy conserving, see brdf())
// as in learnopengl's PBR chapters (Karis 2013, "Real Shading in Unreal Engine 4"), with
// Filament's visibility term V = G2 / (4 (n·l)(n·v)) in place of G / (4 (n·l)(n·v)).
// Roughness is perceptual; the GGX alpha is roughness^2 (Burley 2012). Every direction is
// unit length and points away from the surface; colours are linear RGB with w = 0.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include "rt2/shading/brdf_lut.h"
#include "rt2/geometry/ray.h"

namespace rt2 {

// The smallest GGX alpha the analytic lights see (PbrSurface::alpha). At alpha = 0 the
// distribution is a delta: a point light, being a single direction, would never show a
// highlight on a perfectly smooth surface. The floor is Filament's MIN_ROUGHNESS (its
// perceptual roughness 0.045, squared): at alpha = 0.002 the peak of D is
// 1 / (pi alpha^2) ~ 8e4, a highlight a point light can make visible without turning
// every pixel it touches into a firefly.
// The image-based lighting (environment.h) does not need it: it is prefiltered.
inline constexpr float kMinAlpha = 0.002f;

// GGX / Trowbridge-Reitz normal distribution, D = a^2 / (pi ((n·h)^2 (a^2 - 1) + 1)^2),
// normalised so that the integral of D(h) (n·h) over the hemisphere is 1. 0 for n·h <= 0.
// alpha > 0 (at 0, D is a delta and this returns 0/0 at n·h = 1).
//
// The second form takes sin^2 of the angle between n and h as well, computed by the caller
// as |n x h|^2: the denominator is then sin^2 + (n·h)^2 a^2 without the cancellation of
// 1 - (n·h)^2 near the peak, where (n·h)^2 has an absolute error of ~1e-7 and the term it
// is compared with, a^2, is 4e-6 at kMinAlpha (Filament computes D so for half floats).
inline float ggx_d(float n_dot_h, float sin2_h, float alpha) {
  if (n_dot_h <= 0.0f) return 0.0f;
  const float a2 = alpha * alpha;
  const float k = sin2_h + n_dot_h * n_dot_h * a2;
  return a2 / (std::numbers::pi_v<float> * k * k);
}
inline float ggx_d(float n_dot_h, float alpha) {
  return ggx_d(n_dot_h, (1.0f - n_dot_h) * (1.0f + n_dot_h), alpha);
}

// Height-correlated Smith visibility V = G2 / (4 (n·l)(n·v)) (Heitz 2014, eq. 99; Filament
// 4.4.2): 0.5 / (n·l sqrt((n·v)^2 (1 - a^2) + a^2) + n·v sqrt((n·l)^2 (1 - a^2) + a^2)).
// Symmetric in n·v and n·l, bit for bit. 0 where the denominator is 0 (both cosines 0).
inline float smith_visibility(float n_dot_v, float n_dot_l, float alpha) {
  const float a2 = alpha * alpha;
  const float g_v = n_dot_l * std::sqrt(n_dot_v * n_dot_v * (1.0f - a2) + a2);
  const float g_l = n_dot_v * std::sqrt(n_dot_l * n_dot_l * (1.0f - a2) + a2);
  const float denom = g_v + g_l;
  return denom > 0.0f ? 0.5f / denom : 0.0f;
}

// (1 - cos)^5 with cos clamped to [0, 1] by std::clamp (NaN stays NaN).
inline float schlick_weight(float cos_theta) {
  const float m = 1.0f - std::clamp(cos_theta, 0.0f, 1.0f);
  const float m2 = m * m;
  return m2 * m2 * m;
}

// Schlick's Fresnel, F = F0 + (1 - F0)(1 - cos)^5: F0 at normal incidence, 1 at grazing.
inline vec4 fresnel_schlick(float cos_theta, const vec4& f0) {
  return f0 + (vec4(1.0f, 1.0f, 1.0f) - f0) * schlick_weight(cos_theta);
}

// A material at a shaded point, prepared once for every light and the environment.
struct PbrSurface {
  vec4 diffuse;     // the Lambert colour (base_color); kD is applied in brdf()
  vec4 f0;          // specular reflectance at normal incidence
  float alpha;      // GGX alpha for the analytic lights: max(roughness^2, kMinAlpha)
  float roughness;  // perceptual roughness in [0, 1], for Environment::specular and the LUT
  float metallic;   // [0, 1]
  // diffuse (1 - metallic) / (pi (1 - E_avg)): the part of kD diffuse / pi that does not
  // depend on the directions (set by pbr_surface and set_diffuse).
  vec4 diffuse_scale;
};

// The lobe's directional albedo E = F0 A + B at n·v = mu (brdf_lut.h).
inline vec4 specular_albedo(const PbrSurface& s, float mu) {
  const SplitSum e = split_sum(mu, s.roughness);
  return s.f0 * e.a + vec4(e.b, e.b, e.b);
}

// Sets the surface's diffuse colour (and diffuse_scale with it).
inline void set_diffuse(PbrSurface& s, const vec4& diffuse) {
  s.diffuse = diffuse;
  const SplitSum avg = split_sum_average(s.roughness);
  const vec4 keep = vec4(1.0f, 1.0f, 1.0f) - (s.f0 * avg.a + vec4(avg.b, avg.b, avg.b));
  const vec4 safe = mlib::max(keep, vec4(1e-6f, 1e-6f, 1e-6f, 1.0f));
  s.diffuse_scale = diffuse * ((1.0f - s.metallic) * std::numbers::inv_pi_v<float>) / safe;
}

// glTF's metallic-roughness: F0 = 0.04 (1 - metallic) + base_color metallic (0.04: the
// reflectance of a dielectric of refractive index 1.5). metallic and roughness are
// clamped to [0, 1] by std::clamp (NaN stays NaN; Scene::validate rejects it).
inline PbrSurface pbr_surface(const vec4& base_color, float metallic, float roughness) {
  const float m = std::clamp(metallic, 0.0f, 1.0f);
  const float r = std::clamp(roughness, 0.0f, 1.0f);
  const float d = 0.04f * (1.0f - m);
  PbrSurface s{base_color, vec4(d, d, d) + base_color * m, std::max(r * r, kMinAlpha), r, m, {}};
  set_diffuse(s, base_color);
  return s;
}

// The same with a transmission (KHR_materials_transmission): the share `transmission`
// (1 - metallic) of what is not reflected is refracted instead of diffused.
inline PbrSurface pbr_surface(const vec4& base_color, float metallic, float roughness,
                              float transmission) {
  PbrSurface s = pbr_surface(base_color, metallic, roughness);
  const float t = transmission * (1.0f - s.metallic);
  if (t > 0.0f) set_diffuse(s, base_color * (1.0f - t));
  return s;
}

// The diffuse share. The text (reference/pbr-chapter.txt, after learnopengl) takes
// kD = (1 - F(h·v)) (1 - metallic): the Fresnel of the one microfacet that mirrors l into
// v stands for all the light the specular lobe reflects. That is not energy conserving: a
// white dielectric seen at grazing angles reflects more light than it receives (1.84 times
// at roughness 0.05 and 89 degrees), because the lobe then reflects most of the light and
// the diffuse still adds almost all of its own. rt2 replaces the one Fresnel factor by
// what the whole lobe reflects, its directional albedo E (brdf_lut.h), on both sides so
// that f stays reciprocal (Kelemen and Szirmay-Kalos 2001; Kulla and Conty 2017): the
// diffuse term then reflects exactly (1 - E(v)) of the light a white one would, and the
// BRDF's albedo E(v) + (1 - E(v)) diffuse never exceeds 1. Where the lobe reflects little
// (a dielectric seen head-on, E ~ 0.04) the two shares agree within a few per cent.
//
// f(l, v), the BRDF itself (not times n·l): kD diffuse / pi + D V F, F = F(h·v), kD as
// in the file's header. n, v, l unit length; 0 when l or v is at or below the surface. `e_v` is
// specular_albedo(s, n·v), which a caller shading many lights computes once. Reciprocal
// bit for bit when e_v is: h·v is taken as the mean of h·v and h·l (equal in exact
// arithmetic), and the visibility and kD terms are symmetric.
inline vec4 brdf(const PbrSurface& s, const vec4& n, const vec4& v, const vec4& l,
                 const vec4& e_v) {
  const float n_dot_l = dot(n, l);
  const float n_dot_v = dot(n, v);
  if (!(n_dot_l > 0.0f && n_dot_v > 0.0f)) return vec4();
  const vec4 h = normalize(v + l);
  const float n_dot_h = dot(n, h);
  const vec4 n_x_h = cross(n, h);
  const float h_dot_v = 0.5f * (float(dot(h, v)) + float(dot(h, l)));
  const vec4 f = fresnel_schlick(h_dot_v, s.f0);
  const float dv = ggx_d(n_dot_h, float(dot(n_x_h, n_x_h)), s.alpha) *
                   smith_visibility(n_dot_v, n_dot_l, s.alpha);
  const vec4 one(1.0f, 1.0f, 1.0f);
  return s.diffuse_scale * (one - e_v) * (one - specular_albedo(s, n_dot_l)) + f * dv;
}
inline vec4 brdf(const PbrSurface& s, const vec4& n, const vec4& v, const vec4& l) {
  return brdf(s, n, v, l, specular_albedo(s, float(dot(n, v))));
}

// f(l, v) n·l: what the renderer multiplies by a light's radiance.
inline vec4 brdf_cos(const PbrSurface& s, const vec4& n, const vec4& v, const vec4& l) {
  return brdf(s, n, v, l) * std::max(float(dot(n, l)), 0.0f);
}

}  // namespace rt2
