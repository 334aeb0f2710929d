// rt2/bvh/accel.cpp — compiling a Scene's geometry into its trees (see accel.h).
#include "rt2/bvh/accel.h"

#include <algorithm>
#include <cstdint>
#include <string>

#include "rt2/base/error.h"
#include "rt2/base/memory.h"
#include "rt2/scene/scene.h"

namespace rt2 {

namespace {

// The triangle tree: build, then lay the triangles out in leaf order and collapse.
void build_triangles(const Scene& scene, const BvhConfig& config, Accel& acc) {
  // Triangle i of the scene is face i - first[j] of mesh j, the last mesh with first[j] <= i:
  // found by a search over the meshes, not read from a table of every triangle's mesh and
  // face (16 bytes a triangle of fresh memory, 23 MB for 1.4M triangles).
  std::vector<std::uint32_t> first;
  first.reserve(scene.meshes.size());
  std::uint32_t total = 0;
  bool any_normals = false, any_texcoords = false;
  for (const Mesh& m : scene.meshes) {
    any_normals |= !m.normals.empty() && !m.faces.empty();
    any_texcoords |= !m.texcoords.empty() && !m.faces.empty();
    first.push_back(total);
    total += static_cast<std::uint32_t>(m.faces.size());
  }
  const auto mesh_of = [&](std::uint32_t i) {
    return std::size_t(std::upper_bound(first.begin(), first.end(), i) - first.begin()) - 1;
  };
  // Each box made where the builder stores it. The binary tree is read once, by the
  // collapse below, and not kept.
  const Bvh bvh = build_bvh(
      total,
      [&](std::uint32_t i) {
        const std::size_t j = mesh_of(i);
        const Mesh& m = scene.meshes[j];
        Aabb b;
        for (std::uint32_t v : m.faces[i - first[j]]) b.grow(m.positions[v]);
        return b;
      },
      config);
  acc.stats = bvh.stats;
  acc.tris.reserve(bvh.order.size());
  acc.tri_materials.reserve(bvh.order.size());
  if (any_normals) acc.tri_normals.reserve(bvh.order.size());
  if (any_texcoords) acc.tri_texcoords.reserve(bvh.order.size());
  for (std::uint32_t k : bvh.order) {
    const std::size_t j = mesh_of(k);
    const Mesh& m = scene.meshes[j];
    const std::uint32_t face = k - first[j];
    const auto& f = m.faces[face];
    const Triangle tri = Triangle::make(m.positions[f[0]], m.positions[f[1]], m.positions[f[2]]);
    acc.tris.push_back(tri);
    acc.tri_materials.push_back(m.face_materials[face]);
    if (any_texcoords) {
      if (m.texcoords.empty())
        acc.tri_texcoords.push_back({});
      else
        acc.tri_texcoords.push_back({m.texcoords[f[0]], m.texcoords[f[1]], m.texcoords[f[2]]});
    }
    if (!any_normals) continue;
    if (m.normals.empty()) {
      const vec4 nf = normalize(tri.n);
      acc.tri_normals.push_back({nf, nf, nf});
    } else {
      acc.tri_normals.push_back({m.normals[f[0]], m.normals[f[1]], m.normals[f[2]]});
    }
  }
  with_bvh_width(acc.isa, [&](auto width) {
    constexpr int N = decltype(width)::value;
    acc.wide<N>() = collapse_bvh<N>(bvh, acc.tris, acc.blocks);
    acc.wide_nodes = static_cast<std::uint32_t>(acc.wide<N>().nodes.size());
  });
}

void build_spheres(const Scene& scene, const BvhConfig& config, Accel& acc) {
  std::vector<Aabb> boxes;
  boxes.reserve(scene.spheres.size());
  for (const Sphere& s : scene.spheres) {
    const vec4 r(s.radius, s.radius, s.radius);
    Aabb b;
    b.grow(s.center - r);
    b.grow(s.center + r);
    boxes.push_back(b);
  }
  acc.sphere_bvh = build_bvh(boxes, config);
  acc.sphere_bvh.nodes.shrink_to_fit();  // kept: not the two nodes per sphere reserved
  for (std::uint32_t k : acc.sphere_bvh.order) {
    acc.spheres.push_back(scene.spheres[k]);
    acc.sphere_materials.push_back(scene.sphere_materials[k]);
  }
}

}  // namespace

Accel Accel::build(const Scene& scene, const BvhConfig& config, Isa isa) {
  const std::uint64_t triangles = scene.triangle_count();
  const std::uint64_t need = triangles * kBytesPerTriangle, have = available_memory();
  if (need > have)
    throw Error("the scene's " + std::to_string(triangles) + " triangles need about " +
                memory_size(need) + " to build and trace; " + memory_size(have) +
                " of memory is available");
  Accel acc;
  acc.isa = isa;
  build_triangles(scene, config, acc);
  build_spheres(scene, config, acc);
  acc.planes = scene.planes;
  acc.plane_materials = scene.plane_materials;
  return acc;
}

std::size_t Accel::bvh_bytes() const {
  return bvh4.nodes.size() * sizeof(WideNode<4>) + bvh8.nodes.size() * sizeof(WideNode<8>) +
         bvh16.nodes.size() * sizeof(WideNode<16>) + blocks.size() * sizeof(TriangleBlock) +
         sphere_bvh.nodes.size() * sizeof(BvhNode) +
         sphere_bvh.order.size() * sizeof(std::uint32_t);
}

WideSah Accel::tree_sah() const {
  return with_bvh_width(isa, [&](auto width) {
    return wide_sah(wide<decltype(width)::value>(), blocks.data());
  });
}

}  // namespace rt2
