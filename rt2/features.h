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
  // Not a property of the scene but a render setting: triangles use the watertight test
  // (geometry/triangle.h) instead of the thesis's fast one.
  kWatertight = 1u << 6,
};
// Every content feature: the generic kernel (it keeps the kWatertight choice).
inline constexpr unsigned kAllFeatures = 63;
inline constexpr unsigned kFeatureCombinations = 128;

// The watertight test only matters when there are triangles; other combinations with the
// bit forward to the kernel without it, so only 96 kernels are compiled.
constexpr unsigned normalize_features(unsigned f) {
  return (f & kTriangles) ? f : (f & ~unsigned(kWatertight));
}

template <unsigned F, unsigned Bit>
inline constexpr bool has_feature = (F & Bit) != 0;

// "reflection+specular+spheres+triangles" (or "none").
std::string feature_names(unsigned features);

}  // namespace rt2
