// rt2/scene/mesh.h — an indexed triangle mesh as loaded or generated, before acceleration.
//
// Positions (w = 0), optional per-vertex normals (same count as positions, or empty for
// flat shading) and texture coordinates (same count, or empty), faces as vertex-index
// triples, and a material index per face (an index into Scene::materials). Accel turns
// meshes into precomputed Triangles in BVH order.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "rt2/geometry/aabb.h"

namespace rt2 {

struct Mesh {
  std::string name;  // file name or generator name, for messages
  std::vector<vec4> positions;
  std::vector<vec4> normals;  // empty, or one unit normal per position
  // Texture coordinates: empty, or one (u, v) per position. Image row 0 is v = 1 (OBJ's
  // convention; glTF's v, whose row 0 is v = 0, is flipped by its loader).
  std::vector<std::array<float, 2>> texcoords;
  std::vector<std::array<std::uint32_t, 3>> faces;
  std::vector<std::uint32_t> face_materials;  // one per face

  std::size_t triangle_count() const { return faces.size(); }
  Aabb bounds() const;
  // Appends `other` (indices shifted).
  void append(const Mesh& other);
  // Removes faces that are degenerate (zero or non-finite area) or that reference a vertex
  // out of range; returns how many were removed.
  std::size_t drop_degenerate();
};

// Faces that drop_degenerate drops although they are not degenerate: their area, positive
// and finite in double precision, overflows a float (coordinates too large) or underflows to
// 0 (too small).
struct AreaOutOfRange {
  std::size_t too_large = 0, too_small = 0;
};
AreaOutOfRange area_out_of_range(const Mesh& mesh);

// An affine transform applied to a mesh at load: scale, then rotate (degrees about x, then
// y, then z), then translate. Normals are transformed by the inverse transpose.
struct Transform {
  vec4 scale{1.0f, 1.0f, 1.0f};
  vec4 rotate_degrees{0.0f, 0.0f, 0.0f};
  vec4 translate{0.0f, 0.0f, 0.0f};
};

void apply_transform(Mesh& mesh, const Transform& xf);

}  // namespace rt2
