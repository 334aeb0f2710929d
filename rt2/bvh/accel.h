// rt2/bvh/accel.h — a scene's geometry compiled for tracing: a wide BVH over the triangles, a
// binary BVH over the spheres, and the unbounded planes.
//
// Primitives are kept per kind in contiguous arrays (no virtual call per test): triangles
// in their meshes' face order, so that a triangle's index, which decides ties at equal t, is
// the same whatever tree is built or refit over them; spheres in the leaf order of their
// tree. Triangles: the binary SAH tree (bvh/build.h) collapsed into
// nodes of 4, 8 or 16 children, the width of the instruction set chosen for tracing
// (rt2/base/isa.h), whose leaves are TriangleBlocks of four triangles tested together; `tris`
// keeps each triangle whole for shading. Spheres (usually few) keep the binary tree. The
// queries (closest hit, transmittance) are compiled per instruction set in the render
// kernel (rt2/kernel/).
//
// Two levels: an instanced mesh (scene/instance.h) has a wide tree of its own over its
// triangles in its own coordinates (they share `blocks` and `tris`); a binary tree over the
// instances' world boxes sits beside the world's trees. A ray enters an instance through its
// inverse transform, unnormalised, so that t stays a distance in the world.
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
#include "rt2/scene/instance.h"
#include "rt2/scene/material.h"

namespace rt2 {

struct Scene;

// An instance as the traversal reads it (scene/instance.h).
struct TracedInstance {
  AffineColumns to_object;  // world -> the mesh's coordinates (rays)
  AffineColumns to_world;   // the mesh's coordinates -> world (hit points, triangles)
  AffineColumns normals;    // shading normals to the world: A^-T (c[3] = 0)
  std::uint32_t mesh = 0;   // its tree: Accel::mesh_trees
  std::uint32_t material = kMeshMaterials;  // or every face's material
  bool identity = false;     // rays enter unchanged
  bool mirror = false;       // determinant < 0: geometric normals turned back (instance.h)
};

// The trees of one width, per instanced mesh.
struct MeshTrees {
  std::vector<WideBvh<4>> bvh4;
  std::vector<WideBvh<8>> bvh8;
  std::vector<WideBvh<16>> bvh16;
};

struct Accel {
  Isa isa = Isa::sse41;  // what the trees were built for: bvh_width(isa) children per node

  // Triangles: the wide tree for the ISA's width (the other one stays empty), its leaf
  // blocks, and per triangle (by the index blocks hold) its data for shading.
  WideBvh<4> bvh4;
  WideBvh<8> bvh8;
  WideBvh<16> bvh16;
  TriangleBlocks blocks;
  mlib::HugePageBuffer<Triangle> tris;  // on huge pages once large: read per hit
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

  // Instances: per instanced mesh its tree (the ISA's width), the instances in the scene's
  // order (Scene::instances), and a binary tree over their world boxes whose leaf
  // [first, first + count) holds instances[instance_bvh.order[first ...]]. A hit inside one
  // names it by its index in the scene (Hit::instance), whatever the tree.
  MeshTrees mesh_trees;
  Bvh instance_bvh;
  std::vector<TracedInstance> instances;

  // Per triangle tree (the world's, then each instanced mesh's in Scene::instanced_meshes
  // order): its triangles, tris[first, first + count) in their meshes' face order, and its
  // cost as built (wide_sah: nodes + leaves), against which refit weighs the refit tree's.
  struct TreeRecord {
    std::uint32_t first = 0, count = 0;
    double built_cost = 0.0;
  };
  std::vector<TreeRecord> trees;

  // Statistics of the triangle tree: the binary build (time, nodes, depth) and the wide
  // tree's node and leaf counts.
  BvhStats stats;
  std::uint32_t wide_nodes = 0;

  // Builds every tree with `config`, the triangle trees `bvh_width(isa)` wide.
  static Accel build(const Scene& scene, const BvhConfig& config, Isa isa = best_isa());

  // Refits the trees to `scene`, the scene they were built from with its meshes' vertices,
  // normals and texture coordinates moved (Scene::same_topology): each tree whose
  // triangles moved keeps its shape and takes new boxes (refit_bvh, wide_bvh.h); the spheres'
  // tree is rebuilt with `config`, the planes copied and the instances placed, with
  // `threads` OpenMP threads (<= 0: all). Returns the largest growth of a refit tree's cost
  // over its cost as built (1 when none grew): the caller rebuilds when it is too large.
  // Throws rt2::Error when a tree's triangle count differs from the scene's.
  double refit(const Scene& scene, const BvhConfig& config, int threads = 0);

  // Rebuilds the top level for `instances` (the scene's, moved; the same meshes): their
  // records and the tree over their boxes, with `threads` OpenMP threads (<= 0: all). Up
  // to kSahInstances instances the tree is a binned SAH tree (build_bvh), which rays walk
  // faster (1,000 orbiting boxes: 1.14x the frame rate of scripts/make-animated-scene);
  // above, a linear BVH, which builds faster (10^6 instances with their records: 64 ms at
  // 2 threads).
  void place_instances(const std::vector<Instance>& instances, int threads = 0);
  static constexpr std::size_t kSahInstances = 4096;

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
  // Instanced mesh m's tree of width N.
  template <int N>
  const WideBvh<N>& mesh_tree(std::uint32_t m) const {
    if constexpr (N == 16)
      return mesh_trees.bvh16[m];
    else if constexpr (N == 8)
      return mesh_trees.bvh8[m];
    else
      return mesh_trees.bvh4[m];
  }

  // Bytes of the acceleration structure: tree nodes and leaf blocks (what a ray walks), the
  // instances and their tree, not the shading data (tris, materials, normals).
  std::size_t bvh_bytes() const;

  // The triangle tree's surface area cost in Embree's terms (wide_sah, bvh/wide_bvh.h).
  WideSah tree_sah() const;
  // Whether the triangle tree's nodes are quantized (NodeLayout).
  bool quantized_nodes() const {
    return with_bvh_width(isa,
                          [&](auto width) { return wide<decltype(width)::value>().quantized; });
  }

  // Branch-free over the kinds: a batch's hits mix them unpredictably (a plane's tag, or any
  // other, reads the planes'). A hit in an instance takes the instance's material if it has
  // one.
  std::uint32_t material_of(PrimRef p, std::uint32_t instance = kNoInstance) const {
    const std::uint32_t* const of_kind[4] = {tri_materials.data(), sphere_materials.data(),
                                             plane_materials.data(), plane_materials.data()};
    const std::uint32_t own = of_kind[prim_tag(p) >> 30][prim_index(p)];
    if (instance == kNoInstance) return own;
    const std::uint32_t m = instances[instance].material;
    return m == kMeshMaterials ? own : m;
  }
};

}  // namespace rt2
