// rt2/bvh/accel.h — a scene's geometry compiled for tracing: a wide BVH over the triangles, a
// binary BVH over the spheres, and the unbounded planes.
//
// Primitives are kept per kind in contiguous arrays (no virtual call per test), each in the
// leaf order of its tree. Triangles: the binary SAH tree (bvh/build.h) collapsed into
// nodes of 4, 8 or 16 children, the width of the instruction set chosen for tracing
// (rt2/base/isa.h), whose leaves are TriangleBlocks of four triangles tested together; `tris`
// keeps each triangle whole for shading. Spheres (usually few) keep the binary tree. The
// queries (closest hit, transmittance) are compiled per instruction set in the render
// kernel (rt2/kernel/).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "rt2/bvh/build.h"
#include "rt2/bvh/wide_bvh.h"
#include "rt2/geometry/plane.h"
#include "rt2/geometry/sphere.h"
#include "rt2/geometry/triangle.h"
#include "rt2/geometry/triangle_block.h"
#include "rt2/base/isa.h"
#include "rt2/scene/material.h"

namespace rt2 {

struct Scene;

struct Accel {
  Isa isa = Isa::sse41;  // what the trees were built for: bvh_width(isa) children per node

  // Triangles: the wide tree for the ISA's width (the other one stays empty), its leaf
  // blocks, and per triangle (by the index blocks hold) its data for shading.
  WideBvh<4> bvh4;
  WideBvh<8> bvh8;
  WideBvh<16> bvh16;
  TriangleBlocks blocks;
  mlib::HugePageVector<Triangle> tris;  // on huge pages once large: read per hit
  std::vector<std::uint32_t> tri_materials;
  std::vector<std::array<vec4, 3>> tri_normals;  // per-vertex normals; empty if all flat
  // Per-vertex texture coordinates (u, v); empty if no mesh has any (then all are 0).
  std::vector<std::array<std::array<float, 2>, 3>> tri_texcoords;

  // Spheres: a binary tree whose leaf [first, first + count) holds spheres[first ...].
  Bvh sphere_bvh;
  std::vector<Sphere> spheres;
  std::vector<std::uint32_t> sphere_materials;

  std::vector<Plane> planes;
  std::vector<std::uint32_t> plane_materials;

  // Statistics of the triangle tree: the binary build (time, nodes, depth) and the wide
  // tree's node and leaf counts.
  BvhStats stats;
  std::uint32_t wide_nodes = 0;

  // Builds both trees with `config`, the triangle tree `bvh_width(isa)` wide.
  static Accel build(const Scene& scene, const BvhConfig& config, Isa isa = best_isa());

  // The triangle tree of width N (4, 8 or 16).
  template <int N>
  const WideBvh<N>& wide() const {
    if constexpr (N == 16)
      return bvh16;
    else if constexpr (N == 8)
      return bvh8;
    else
      return bvh4;
  }
  template <int N>
  WideBvh<N>& wide() {
    return const_cast<WideBvh<N>&>(static_cast<const Accel&>(*this).wide<N>());
  }

  // Bytes of the acceleration structure: tree nodes and leaf blocks (what a ray walks), not
  // the shading data (tris, materials, normals).
  std::size_t bvh_bytes() const;

  // The triangle tree's surface area cost in Embree's terms (wide_sah, bvh/wide_bvh.h).
  WideSah tree_sah() const;

  // Branch-free: a batch's hits mix the kinds unpredictably (a plane's tag, or any other,
  // reads the planes').
  std::uint32_t material_of(PrimRef p) const {
    const std::uint32_t* const of_kind[4] = {tri_materials.data(), sphere_materials.data(),
                                             plane_materials.data(), plane_materials.data()};
    return of_kind[prim_tag(p) >> 30][prim_index(p)];
  }
};

}  // namespace rt2
