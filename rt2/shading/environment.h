// rt2/shading/environment.h — the light from far away: an environment map seen as the background
// and prefiltered for image-based lighting with the split-sum approximation (Karis 2013,
// "Real Shading in Unreal Engine 4"; learnopengl's IBL chapters).
//
// A surface lit by the environment reflects
//   diffuse:  (1 - metallic)(1 - E(v)) base_color irradiance(n)
//   specular: specular(r, roughness) E(v),  E(v) = F0 A + B from brdf_lut.h's split_sum
// with r the mirror direction of v. The factories prefilter once per scene (in parallel
// with OpenMP); the lookups are bilinear and cheap, made per shaded point. Maps are
// equirectangular with the convention of rt2/shading/equirect.h (y up, row 0 at +y).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

#include "rt2/shading/equirect.h"
#include "rt2/geometry/ray.h"

namespace rt2 {

// E(n) / pi as 9 spherical-harmonic coefficients (RGB): the irradiance environment map of
// Ramamoorthi and Hanrahan 2001. Irradiance is the radiance convolved with the clamped
// cosine, whose bands above 2 carry under 1 % of it: 9 numbers per channel represent it
// within a few per cent of the exact convolution everywhere (exactly for light that varies
// linearly over the sphere: a constant sky, a bright upper hemisphere), and a lookup is a
// few multiply-adds, no trigonometry and no memory beyond 9 vectors.
// The real spherical harmonics of bands 0 ... 2 at unit direction d, in the order of
// IrradianceSh::c (Ramamoorthi and Hanrahan 2001, eq. 3).
inline std::array<float, 9> sh9(const vec4& d) {
  const float x = d[0], y = d[1], z = d[2];
  return {0.282095f,          0.488603f * y,        0.488603f * z,
          0.488603f * x,      1.092548f * x * y,    1.092548f * y * z,
          0.315392f * (3.0f * z * z - 1.0f), 1.092548f * x * z, 0.546274f * (x * x - y * y)};
}

struct IrradianceSh {
  std::array<vec4, 9> c{};  // bands 0, 1 (y, z, x), 2 (xy, yz, 3z^2 - 1, xz, x^2 - y^2)
};

// rotation_degrees turns the environment about +y, right-handed (90 degrees turn +z into
// +x): what the map holds at direction m is seen at direction R_y(rotation) m, which is
// the same as looking the map up at u + rotation / 360.
//
// What the prefiltered maps hold (all linear RGB):
// * irradiance: E(n) / pi = (1/pi) integral of L(w) max(0, n·w) dw, so that a Lambert
//   surface of albedo c reflects c irradiance(n); a constant environment c gives c. Held
//   as spherical harmonics (IrradianceSh above), projected from the source by quadrature:
//   cheaper per shaded point than a convolved map's direction-to-uv conversion and
//   bilinear lookup.
// * specular: kSpecularLevels maps at roughness k / (kSpecularLevels - 1): level 0 is the
//   source (at most 512 texels on each side), level k halves the resolution of level k-1
//   (not below 32 x 16). Each texel is GGX-prefiltered radiance around its direction under
//   Karis's n = v = r assumption, weighted by n·l, from 128 GGX-distributed Hammersley
//   samples, each read from the source's mip level that matches its solid angle
//   (Colbert and Krivanek 2007, "GPU-Based Importance Sampling": filtered importance
//   sampling, so that few samples do not alias).
// * the split-sum table A, B with integral of f_spec cos = F0 A + B for brdf.h's specular
//   term: brdf_lut.h (one table per process, shared with brdf.h's diffuse term).
class Environment {
 public:
  static constexpr int kSpecularLevels = 6;  // roughness 0, 0.2, ..., 1

  // The same radiance `color` from every direction (lookups return it exactly). Builds
  // 1 x 1 maps: it does not run the prefilter.
  static Environment uniform(const vec4& color);
  // An image of width x height texels, linear RGB floats, row-major, 3 per texel, row 0
  // at the top (+y), times `intensity` (>= 0). Negative values become 0 and so do NaN and
  // infinities (counted: replaced_values()). Throws rt2::Error for an empty image, a size
  // that does not match rgb, or a negative or non-finite intensity or rotation.
  static Environment from_image(int width, int height, std::vector<float> rgb, float intensity,
                                float rotation_degrees);
  // The most memory (bytes) from_image holds at once for a width x height image, its
  // argument included: to check before an image file is read.
  static double bytes_for_image(int width, int height);
  // A procedural clear sky, 256 x 128: a blue gradient from the zenith to a brighter
  // horizon, a darker brown ground below it, and a sun (a disk of 2 degrees' radius with a
  // soft edge and a glow) towards sun_direction, given in the map's frame (before the
  // rotation). The sun adds about half as much irradiance as the sky; it is hidden when
  // below the horizon. Deterministic. Throws rt2::Error for a zero or non-finite
  // sun_direction, or a negative or non-finite intensity or rotation.
  static Environment sky(const vec4& sun_direction, float intensity, float rotation_degrees);

  // The radiance arriving from direction `dir` (unit), i.e. the background: the source map.
  vec4 radiance(const vec4& dir) const { return radiance_at(map_uv(dir)); }
  // The same at the map coordinates of dir, map_uv(dir).
  vec4 radiance_at(Uv uv) const { return source_.bilinear(uv); }
  // E(n) / pi for the unit normal n (see above).
  vec4 irradiance(const vec4& n) const {
    const std::array<float, 9> b = sh9(n);
    vec4 e = irradiance_.c[0] * b[0];
    for (std::size_t k = 1; k < 9; ++k) e += irradiance_.c[k] * b[k];
    return e;
  }
  // Prefiltered radiance around the unit reflection direction r; roughness (perceptual) in
  // [0, 1], clamped, interpolated linearly between the two nearest levels.
  vec4 specular(const vec4& r, float roughness) const { return specular_at(map_uv(r), roughness); }
  // The same at the map coordinates of r, map_uv(r).
  vec4 specular_at(Uv uv, float roughness) const {
    const float x = std::clamp(roughness, 0.0f, 1.0f) * float(kSpecularLevels - 1);
    const int k = std::min(int(x), kSpecularLevels - 2);
    const vec4 a = specular_[std::size_t(k)].bilinear(uv);
    const vec4 b = specular_[std::size_t(k) + 1].bilinear(uv);
    return a + (b - a) * (x - float(k));
  }

  // What the lookups read, for the shading lanes (rt2/kernel/environment_lanes.h), which compute
  // the same bits: the coefficients, and map_uv's shift in u.
  const IrradianceSh& irradiance_sh() const { return irradiance_; }
  float u_shift() const { return u_shift_; }
  // u in map space of the world direction d: the rotation is a shift in u.
  Uv map_uv(const vec4& d) const {
    Uv uv = direction_to_uv(d);
    uv.u += u_shift_;
    return uv;
  }

  // Wall-clock seconds the factory spent prefiltering.
  double prefilter_seconds() const { return prefilter_seconds_; }
  // How many input values from_image replaced by 0 (negative, NaN or infinite).
  std::size_t replaced_values() const { return replaced_values_; }

  // The resolution of the maps, for reports and tests.
  const EquirectMap& source_map() const { return source_; }
  const EquirectMap& specular_map(int level) const { return specular_[std::size_t(level)]; }

 private:
  Environment() = default;
  // Prefilters everything from source_ (with the rotation already set).
  void prefilter();
  EquirectMap source_;
  IrradianceSh irradiance_;
  std::vector<EquirectMap> specular_;  // kSpecularLevels
  float u_shift_ = 0.0f;               // rotation / 360
  double prefilter_seconds_ = 0.0;
  std::size_t replaced_values_ = 0;
};

}  // namespace rt2
