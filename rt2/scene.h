// rt2/scene.h — a scene as described: camera, lights, materials and geometry.
//
// This is the description a loader fills; rt2::Accel compiles its geometry into BVH order
// for rendering. Planes are unbounded and stay outside the BVH.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "rt2/camera.h"
#include "rt2/features.h"
#include "rt2/geometry/plane.h"
#include "rt2/geometry/sphere.h"
#include "rt2/material.h"
#include "rt2/mesh.h"

namespace rt2 {

struct Scene {
  Camera camera;
  vec4 ambient{0.2f, 0.2f, 0.2f};      // I_amb, the ambient light
  vec4 background{0.0f, 0.0f, 0.0f};  // colour of rays that hit nothing

  std::vector<Material> materials;
  std::vector<std::string> material_names;  // parallel to materials
  std::vector<Light> lights;

  std::vector<Sphere> spheres;
  std::vector<std::uint32_t> sphere_materials;
  std::vector<Plane> planes;
  std::vector<std::uint32_t> plane_materials;
  std::vector<Mesh> meshes;

  std::size_t degenerate_triangles = 0;  // dropped by the loaders, reported by rt2cpr

  // Adds a material and returns its index.
  std::uint32_t add_material(const std::string& name, const Material& m);
  // Index of the material called `name`, or -1.
  int find_material(const std::string& name) const;

  std::size_t triangle_count() const;
  // Bounds of the bounded geometry (spheres and meshes); empty if there is none.
  Aabb bounds() const;
  // The feature bits this scene needs (see features.h), given how many lights are used.
  unsigned features(std::size_t light_count) const;
  unsigned features() const { return features(lights.size()); }
  // Throws rt2::Error for anything a renderer cannot use: non-finite numbers, material
  // indices out of range, radius <= 0, zero plane normals.
  void validate() const;
};

// Extra lights for `--lights N`: the scene's own lights first, then `total - existing`
// lights placed deterministically on a ring above the scene's bounds (see scene.cpp).
void set_light_count(Scene& scene, std::size_t total);

}  // namespace rt2
