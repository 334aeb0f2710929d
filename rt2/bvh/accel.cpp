// rt2/bvh/accel.cpp — compiling a Scene's geometry into its trees (see accel.h).
#include "rt2/bvh/accel.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <span>
#include <utility>
#include <string>

#include <omp.h>

#include "mlib/fpmode.h"
#include "rt2/base/error.h"
#include "rt2/base/memory.h"
#include "rt2/bvh/linear_build.h"
#include "rt2/scene/scene.h"

namespace rt2 {

namespace {

template <int N>
std::vector<WideBvh<N>>& mesh_trees_of(MeshTrees& t) {
  if constexpr (N == 16)
    return t.bvh16;
  else if constexpr (N == 8)
    return t.bvh8;
  else
    return t.bvh4;
}

// Below some 64k triangles a second thread costs more than it saves (a build's or a refit's
// pass over the triangles).
constexpr std::uint32_t kParallelTriangles = 65536;

// Which per-vertex columns the triangles carry: normals and texture coordinates, for all
// triangles when any mesh (the world's or an instanced one) has them.
struct TriangleColumns {
  bool normals = false, texcoords = false;
};

// Triangle k of `meshes` (face k - first[j] of mesh j, the last mesh with first[j] <= k):
// found by a search over the meshes, not read from a table of every triangle's mesh and
// face (16 bytes a triangle of fresh memory, 23 MB for 1.4M triangles).
class MeshFaces {
 public:
  explicit MeshFaces(std::span<const Mesh> meshes) : meshes_(meshes) {
    first_.reserve(meshes.size());
    for (const Mesh& m : meshes) {
      first_.push_back(total_);
      total_ += static_cast<std::uint32_t>(m.faces.size());
    }
  }
  std::uint32_t total() const { return total_; }
  std::pair<const Mesh*, std::uint32_t> operator()(std::uint32_t k) const {
    const std::size_t j =
        std::size_t(std::upper_bound(first_.begin(), first_.end(), k) - first_.begin()) - 1;
    return {&meshes_[j], k - first_[j]};
  }

 private:
  std::span<const Mesh> meshes_;
  std::vector<std::uint32_t> first_;
  std::uint32_t total_ = 0;
};

// Writes triangle `index` of acc's arrays: face `face` of `m`, whose triangle is `tri`.
void set_triangle(const Mesh& m, std::uint32_t face, const Triangle& tri, TriangleColumns columns,
                  std::size_t index, Accel& acc) {
  const auto& f = m.faces[face];
  acc.tris[index] = tri;
  acc.tri_materials[index] = m.face_materials[face];
  if (columns.texcoords) {
    if (m.texcoords.empty())
      acc.tri_texcoords[index] = {};
    else
      acc.tri_texcoords[index] = {m.texcoords[f[0]], m.texcoords[f[1]], m.texcoords[f[2]]};
  }
  if (columns.normals) {
    if (m.normals.empty()) {
      const vec4 nf = normalize(tri.n);
      acc.tri_normals[index] = {nf, nf, nf};
    } else {
      acc.tri_normals[index] = {m.normals[f[0]], m.normals[f[1]], m.normals[f[2]]};
    }
  }
}

Triangle triangle_of(const Mesh& m, std::uint32_t face) {
  const auto& f = m.faces[face];
  return Triangle::make(m.positions[f[0]], m.positions[f[1]], m.positions[f[2]]);
}

// set_triangle over a triangle acc already holds; returns whether its vertices changed.
bool put_triangle(const Mesh& m, std::uint32_t face, TriangleColumns columns, std::size_t index,
                  Accel& acc) {
  const Triangle tri = triangle_of(m, face);
  const bool moved =
      std::memcmp(&acc.tris[index], &tri, sizeof(Triangle)) != 0;  // bits: -0 is not +0
  set_triangle(m, face, tri, columns, index, acc);
  return moved;
}

// The cost a refit is weighed by: expected nodes entered and blocks tested (wide_sah).
template <int N>
double tree_cost(const WideBvh<N>& bvh, const TriangleBlocks& blocks) {
  const WideSah sah = wide_sah(bvh, blocks.data());
  return sah.nodes + sah.leaves;
}

// A tree over `meshes`' triangles: built, the triangles appended to acc's arrays in the
// meshes' order, then collapsed to width N over acc.blocks (prims indexing acc.tris). Its
// record is appended to acc.trees.
template <int N>
WideBvh<N> build_triangles(std::span<const Mesh> meshes, const BvhConfig& config,
                           TriangleColumns columns, Accel& acc, BvhStats* stats) {
  const MeshFaces faces(meshes);
  // Each box made where the builder stores it. The binary tree is read once, by the
  // collapse below, and not kept.
  const Bvh bvh = build_bvh(
      faces.total(),
      [&](std::uint32_t k) {
        const auto [m, face] = faces(k);
        Aabb b;
        for (std::uint32_t v : m->faces[face]) b.grow(m->positions[v]);
        return b;
      },
      config);
  if (stats) *stats = bvh.stats;
  const std::size_t offset = acc.tris.size(), end = offset + faces.total();
  acc.tris.resize(end);
  acc.tri_materials.resize(end);
  if (columns.normals) acc.tri_normals.resize(end);
  if (columns.texcoords) acc.tri_texcoords.resize(end);
  const std::uint32_t count = faces.total();
  const unsigned mode = mlib::denormal_mode();
#pragma omp parallel if (count >= kParallelTriangles)
  {
    const mlib::DenormalModeScope caller_mode(mode);  // the team computes as one thread
#pragma omp for schedule(static)
    for (std::uint32_t k = 0; k < count; ++k) {
      const auto [m, face] = faces(k);
      set_triangle(*m, face, triangle_of(*m, face), columns, offset + k, acc);
    }
  }
  const std::size_t first_block = acc.blocks.size();
  WideBvh<N> tree = collapse_bvh<N>(bvh, std::span<const Triangle>(acc.tris).subspan(offset),
                                    acc.blocks, config.nodes);
  if (offset != 0)  // the blocks name triangles of the span: shift them to acc.tris'
    for (std::size_t b = first_block; b < acc.blocks.size(); ++b)
      for (std::uint32_t& p : acc.blocks[b].prim)
        if ((p & ~TriangleBlock::kLastBlock) != TriangleBlock::kNoPrim)
          p += static_cast<std::uint32_t>(offset);
  acc.trees.push_back({static_cast<std::uint32_t>(offset), faces.total(),
                       tree_cost(tree, acc.blocks)});
  return tree;
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
  const std::uint64_t triangles = scene.triangle_count(), instances = scene.instances.size();
  const std::uint64_t need = triangles * kBytesPerTriangle + instances * kBytesPerInstance,
                      have = available_memory();
  if (need > have)
    throw Error("the scene's " + std::to_string(triangles) + " triangles" +
                (instances ? " and " + std::to_string(instances) + " instances" : "") +
                " need about " + memory_size(need) + " to build and trace; " +
                memory_size(have) + " of memory is available");
  Accel acc;
  acc.isa = isa;
  TriangleColumns columns;
  for (const auto* meshes : {&scene.meshes, &scene.instanced_meshes})
    for (const Mesh& m : *meshes) {
      columns.normals |= !m.normals.empty() && !m.faces.empty();
      columns.texcoords |= !m.texcoords.empty() && !m.faces.empty();
    }
  with_bvh_width(isa, [&](auto width) {
    constexpr int N = decltype(width)::value;
    acc.wide<N>() = build_triangles<N>(scene.meshes, config, columns, acc, &acc.stats);
    acc.wide_nodes = static_cast<std::uint32_t>(acc.wide<N>().node_count());
    std::vector<WideBvh<N>>& trees = mesh_trees_of<N>(acc.mesh_trees);
    for (const Mesh& m : scene.instanced_meshes) {
      trees.push_back(build_triangles<N>(std::span<const Mesh>(&m, 1), config, columns, acc,
                                         nullptr));
      acc.wide_nodes += static_cast<std::uint32_t>(trees.back().node_count());
    }
  });
  build_spheres(scene, config, acc);
  acc.planes = scene.planes;
  acc.plane_materials = scene.plane_materials;
  acc.place_instances(scene.instances);
  return acc;
}

double Accel::refit(const Scene& scene, const BvhConfig& config, int threads) {
  const int team = threads > 0 ? threads : omp_get_max_threads();
  const TriangleColumns columns{!tri_normals.empty(), !tri_texcoords.empty()};
  double growth = 1.0;
  with_bvh_width(isa, [&](auto width) {
    constexpr int N = decltype(width)::value;
    for (std::size_t t = 0; t < trees.size(); ++t) {
      const std::span<const Mesh> meshes =
          t == 0 ? std::span<const Mesh>(scene.meshes)
                 : std::span<const Mesh>(&scene.instanced_meshes[t - 1], 1);
      std::size_t count = 0;
      for (const Mesh& m : meshes) count += m.faces.size();
      const TreeRecord& record = trees[t];
      if (count != record.count)
        throw Error("refit: the scene's triangles are not those the trees were built over");
      const int tree_team = record.count < kParallelTriangles ? 1 : team;
      bool moved = false;
      std::size_t first = record.first;
      const unsigned mode = mlib::denormal_mode();
      for (const Mesh& m : meshes) {  // mesh by mesh: no search per triangle
        const auto n = static_cast<std::uint32_t>(m.faces.size());
#pragma omp parallel num_threads(tree_team) reduction(|| : moved)
        {
          const mlib::DenormalModeScope caller_mode(mode);  // the team computes as one thread
#pragma omp for schedule(static)
          for (std::uint32_t face = 0; face < n; ++face)
            moved = put_triangle(m, face, columns, first + face, *this) || moved;
        }
        first += n;
      }
      if (!moved) continue;
      WideBvh<N>& tree = t == 0 ? wide<N>() : mesh_trees_of<N>(mesh_trees)[t - 1];
      refit_bvh<N>(tree, tris, blocks, tree_team);
      if (record.built_cost > 0.0)
        growth = std::max(growth, tree_cost(tree, blocks) / record.built_cost);
    }
  });
  spheres.clear();
  sphere_materials.clear();
  build_spheres(scene, config, *this);
  planes = scene.planes;
  plane_materials = scene.plane_materials;
  place_instances(scene.instances, threads);
  return growth;
}

void Accel::place_instances(const std::vector<Instance>& scene_instances, int threads) {
  const std::size_t n = scene_instances.size();
  // Below some 32k instances a second thread costs more than it saves.
  const int team = n < 32768 ? 1 : threads > 0 ? threads : omp_get_max_threads();
  // Scratch kept between frames (named through a reference: inside the parallel loop the
  // thread_local's name would be each thread's own).
  thread_local std::vector<Aabb> scratch;
  std::vector<Aabb>& boxes = scratch;
  boxes.resize(n);
  instances.resize(n);
  // In the scene's order: each instance read and its record written once, in sequence.
  const unsigned mode = mlib::denormal_mode();
  with_bvh_width(isa, [&](auto width) {
    constexpr int N = decltype(width)::value;
#pragma omp parallel num_threads(team)
    {
      const mlib::DenormalModeScope caller_mode(mode);  // the team computes as one thread
#pragma omp for schedule(static)
      for (std::size_t i = 0; i < n; ++i) {
        const Instance& in = scene_instances[i];
        boxes[i] = world_box(mesh_tree<N>(in.mesh).bounds, in.to_world);
        TracedInstance& r = instances[i];
        const Affine to_object = in.to_world.inverse();
        r.to_world = columns_of(in.to_world);
        r.to_object = columns_of(to_object);
        Affine normals;  // A^-T: the transpose of the inverse's linear part
        for (std::size_t a = 0; a < 3; ++a) {
          for (std::size_t b = 0; b < 3; ++b) normals.m[a][b] = to_object.m[b][a];
          normals.m[a][3] = 0.0;
        }
        r.normals = columns_of(normals);
        r.mesh = in.mesh;
        r.material = in.material;
        r.identity = in.to_world.is_identity();
        r.mirror = in.to_world.determinant() < 0.0;
      }
    }
  });
  // Rebuilt every frame, one instance a leaf (entering one costs a transform and a walk of
  // its own): binned SAH up to kSahInstances, a linear BVH above.
  if (n <= kSahInstances) {
    BvhConfig sah;
    sah.max_leaf_size = 1;
    sah.sah_block = 1;
    instance_bvh = build_bvh(boxes, sah);
  } else {
    build_linear_bvh(boxes, team, instance_bvh);
  }
}

std::size_t Accel::bvh_bytes() const {
  std::size_t mesh_nodes = 0;
  for (const auto& t : mesh_trees.bvh4) mesh_nodes += t.node_bytes();
  for (const auto& t : mesh_trees.bvh8) mesh_nodes += t.node_bytes();
  for (const auto& t : mesh_trees.bvh16) mesh_nodes += t.node_bytes();
  return bvh4.node_bytes() + bvh8.node_bytes() + bvh16.node_bytes() +
         blocks.size() * sizeof(TriangleBlock) +
         mesh_nodes + sphere_bvh.nodes.size() * sizeof(BvhNode) +
         sphere_bvh.order.size() * sizeof(std::uint32_t) +
         instance_bvh.nodes.size() * sizeof(BvhNode) +
         instance_bvh.order.size() * sizeof(std::uint32_t) +
         instances.size() * sizeof(TracedInstance);
}

WideSah Accel::tree_sah() const {
  return with_bvh_width(isa, [&](auto width) {
    return wide_sah(wide<decltype(width)::value>(), blocks.data());
  });
}

}  // namespace rt2
