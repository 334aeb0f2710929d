// rt2/scene/material.h — materials: Phong (thesis 3.2) and physically based metallic-roughness
// (glTF 2.0's model; rt2/shading/brdf.h).
#pragma once

#include <cmath>
#include <cstdint>
#include <string>

#include "rt2/geometry/ray.h"

namespace rt2 {

// Which shading a material gets.
enum class Shading : std::uint8_t {
  phong,  // the thesis's model (the fields Ka ... checker below)
  pbr,    // Cook-Torrance GGX metallic-roughness (the fields base_color ... below; brdf.h)
};

// An index into Scene::textures (CompiledScene::textures), or kNoTexture.
inline constexpr std::uint32_t kNoTexture = ~std::uint32_t(0);

// I_local = Ka I_amb + sum over visible lights [Kd I (L·N) + Ks I (R·V)^n];
// I = I_local + Kr I_reflected + Kt I_refracted. Colours are linear RGB in lanes x y z.
struct Material {
  vec4 ambient{0.1f, 0.1f, 0.1f};   // Ka
  vec4 diffuse{0.7f, 0.7f, 0.7f};   // Kd
  vec4 specular{0.0f, 0.0f, 0.0f};  // Ks
  float shininess = 32.0f;          // Phong exponent n (>= 0)
  float reflectivity = 0.0f;        // Kr in [0, 1]
  float transparency = 0.0f;        // Kt in [0, 1]; also how much light passes in shadows
  float ior = 1.5f;                 // refractive index (> 0), used when Kt > 0
  // Optional 3D checker: where floor(x/s) + floor(y/s) + floor(z/s) is odd, Kd is
  // replaced by `diffuse2`. Off when checker_scale is 0.
  vec4 diffuse2{0.1f, 0.1f, 0.1f};
  float checker_scale = 0.0f;

  Shading model = Shading::phong;

  // Physically based (model == pbr), glTF 2.0's metallic-roughness material. Colours are
  // linear RGB. The shading (rt2/shading/brdf.h, the render kernel) takes F0 = 0.04 (1 - metallic)
  // + base_color metallic and the diffuse colour base_color (1 - metallic).
  vec4 base_color{1.0f, 1.0f, 1.0f};
  float metallic = 0.0f;       // [0, 1]
  float roughness = 1.0f;      // perceptual, [0, 1]; the GGX alpha is roughness^2
  vec4 emissive{0.0f, 0.0f, 0.0f};  // radiance the surface emits (>= 0)
  float transmission = 0.0f;   // [0, 1]: the share of the non-reflected light refracted
                               // (KHR_materials_transmission); uses `ior`
  float normal_scale = 1.0f;   // glTF normalTexture.scale

  // Textures (either model): base_color_texture multiplies base_color (pbr) or Kd (phong,
  // MTL's map_Kd), sRGB-encoded; metallic_roughness_texture is linear, roughness in G and
  // metallic in B, multiplying the factors; normal_texture a tangent-space normal map;
  // emissive_texture multiplies emissive, sRGB-encoded. A texture needs texture coordinates
  // (meshes' texcoords; spheres and planes have their own: rt2/kernel/surface_point.h).
  std::uint32_t base_color_texture = kNoTexture;
  std::uint32_t metallic_roughness_texture = kNoTexture;
  std::uint32_t normal_texture = kNoTexture;
  std::uint32_t emissive_texture = kNoTexture;
  // MTL's map_Pr and map_Pm: roughness and metallic each in a grey image (its first
  // channel), multiplying the factors like metallic_roughness_texture's channels.
  std::uint32_t roughness_texture = kNoTexture;
  std::uint32_t metallic_texture = kNoTexture;

  bool has_specular() const { return specular[0] > 0 || specular[1] > 0 || specular[2] > 0; }
  // Phong without a texture or transparency: the shading lanes (phong_lanes.h) take its hits.
  bool plain_phong() const {
    return model == Shading::phong && base_color_texture == kNoTexture && !(transparency > 0.0f);
  }
  // Physically based without a texture or transmission: the shading lanes (pbr_lanes.h)
  // take its hits.
  bool plain_pbr() const {
    return model == Shading::pbr && base_color_texture == kNoTexture &&
           metallic_roughness_texture == kNoTexture && normal_texture == kNoTexture &&
           emissive_texture == kNoTexture && roughness_texture == kNoTexture &&
           metallic_texture == kNoTexture && !(transmission * (1.0f - metallic) > 0.0f);
  }
  // Kd at the world-space point p: `diffuse`, or `diffuse2` on the checker's odd cells.
  // Always inline: the render kernels, compiled per instruction set, call it per hit, and
  // an out-of-line copy would be one symbol with wide and baseline bodies.
  MLIB_INLINE vec4 diffuse_at(const vec4& p) const {
    if (!(checker_scale > 0.0f)) return diffuse;
    const float inv = 1.0f / checker_scale;
    // the cells' sum, unsigned: only its parity matters
    const auto cells = static_cast<unsigned long long>(static_cast<long long>(std::floor(p[0] * inv))) +
                       static_cast<unsigned long long>(static_cast<long long>(std::floor(p[1] * inv))) +
                       static_cast<unsigned long long>(static_cast<long long>(std::floor(p[2] * inv)));
    return (cells & 1) ? diffuse2 : diffuse;
  }
};

}  // namespace rt2
