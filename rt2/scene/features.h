// rt2/scene/features.h — what a scene uses: reflection, refraction, highlights and the kinds of
// primitive, as bits, for reports and tests.
//
// The render kernel is compiled per instruction set (rt2/base/isa.h) and decides per
// material at run time, not per combination of these bits: a kernel per combination would
// multiply the code for next to no gain.
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

// "reflection+specular+spheres+triangles" (or "none").
std::string feature_names(unsigned features);

}  // namespace rt2
