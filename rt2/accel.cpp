// rt2/accel.cpp — compiling a Scene's geometry into BVH leaf order.
#include "rt2/accel.h"

#include "rt2/scene.h"

namespace rt2 {

Accel Accel::build(const Scene& scene, const BvhConfig& config) {
  // Gather every bounded primitive with its box, spheres first then mesh triangles.
  struct Source {
    const Mesh* mesh;
    std::uint32_t face;  // or sphere index when mesh == nullptr
  };
  std::vector<Source> sources;
  std::vector<Aabb> boxes;
  const std::size_t n = scene.spheres.size() + scene.triangle_count();
  sources.reserve(n);
  boxes.reserve(n);
  for (std::uint32_t i = 0; i < scene.spheres.size(); ++i) {
    const Sphere& s = scene.spheres[i];
    const vec4 r(s.radius, s.radius, s.radius);
    Aabb b;
    b.grow(s.center - r);
    b.grow(s.center + r);
    sources.push_back({nullptr, i});
    boxes.push_back(b);
  }
  bool any_normals = false;
  for (const Mesh& m : scene.meshes) {
    any_normals |= !m.normals.empty() && !m.faces.empty();
    for (std::uint32_t f = 0; f < m.faces.size(); ++f) {
      Aabb b;
      for (std::uint32_t v : m.faces[f]) b.grow(m.positions[v]);
      sources.push_back({&m, f});
      boxes.push_back(b);
    }
  }

  Accel acc;
  acc.bvh = build_bvh(boxes, config);
  acc.refs.reserve(n);
  for (std::uint32_t k : acc.bvh.order) {
    const Source& src = sources[k];
    if (!src.mesh) {
      acc.refs.push_back(kSphereTag | static_cast<std::uint32_t>(acc.spheres.size()));
      acc.spheres.push_back(scene.spheres[src.face]);
      acc.sphere_materials.push_back(scene.sphere_materials[src.face]);
      continue;
    }
    const Mesh& m = *src.mesh;
    const auto& f = m.faces[src.face];
    acc.refs.push_back(kTriangleTag | static_cast<std::uint32_t>(acc.tris.size()));
    const Triangle tri = Triangle::make(m.positions[f[0]], m.positions[f[1]], m.positions[f[2]]);
    acc.tris.push_back(tri);
    acc.tri_materials.push_back(m.face_materials[src.face]);
    if (any_normals) {
      if (m.normals.empty()) {
        const vec4 nf = normalize(tri.n);
        acc.tri_normals.push_back({nf, nf, nf});
      } else {
        acc.tri_normals.push_back({m.normals[f[0]], m.normals[f[1]], m.normals[f[2]]});
      }
    }
  }
  acc.planes = scene.planes;
  acc.plane_materials = scene.plane_materials;
  return acc;
}

}  // namespace rt2
