// rt2/features.h — what a scene uses, as compile-time flags for the render kernel.
//
// At load the renderer notes which features the scene needs and runs a kernel specialised
// for exactly that set (a template over these bits), so a scene without glass never pays
// for refraction: the code is not there, not merely skipped. kAllFeatures is the generic
// kernel, which decides the same things per material at run time.
#pragma once

#include <string>

namespace rt2 {

enum Feature : unsigned {
  kReflection = 1u << 0,  // some material has Kr > 0
  kRefraction = 1u << 1,  // some material has Kt > 0 (also: transparent shadows)
  kSpecular = 1u << 2,    // some material has Ks > 0 and the scene has lights
  kSpheres = 1u << 3,
  kPlanes = 1u << 4,
  kTriangles = 1u << 5,
};
inline constexpr unsigned kAllFeatures = 63;
inline constexpr unsigned kFeatureCombinations = 64;

template <unsigned F, unsigned Bit>
inline constexpr bool has_feature = (F & Bit) != 0;

// "reflection+specular+spheres+triangles" (or "none").
std::string feature_names(unsigned features);

}  // namespace rt2
