// rt2/scene/instance.h — a mesh placed in the world by an affine transform, many times over
// without copying its triangles: the two-level tree (rt2/bvh/accel.h) traces each mesh once
// in its own coordinates and enters it through each instance's inverse transform.
//
// A transform that mirrors (determinant < 0) keeps the mesh's front faces in front, as
// glTF asks and as apply_transform (mesh.h) does for flattened meshes.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include "rt2/geometry/aabb.h"
#include "rt2/scene/mesh.h"

namespace rt2 {

// x -> A x + b, row-major: m[r] = (A[r][0], A[r][1], A[r][2], b[r]).
struct Affine {
  std::array<std::array<double, 4>, 3> m{{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}};

  double determinant() const;
  bool is_identity() const;
  bool finite() const;
  // The inverse (the caller checks that the determinant is not 0).
  Affine inverse() const;
  // Point and direction, in double.
  std::array<double, 3> point(const std::array<double, 3>& p) const;
};

// The rotation by `degrees` about x, then y, then z: Rz Ry Rx, row-major.
std::array<std::array<double, 3>, 3> rotation_matrix(const vec4& degrees);
// Scale, then rotate (rotation_matrix), then translate, in double.
Affine affine_of(const Transform& xf);

// The same transform as column vectors for the traversal: x -> c[0] x0 + c[1] x1 + c[2] x2
// + c[3] (w lanes 0), rounded to float.
struct AffineColumns {
  vec4 c[4];

  vec4 point(const vec4& p) const { return ((c[0] * p[0] + c[1] * p[1]) + c[2] * p[2]) + c[3]; }
  // + 0 last: the w lane is +0 whatever the signs of the products
  vec4 direction(const vec4& d) const {
    return ((c[0] * d[0] + c[1] * d[1]) + c[2] * d[2]) + vec4(0.0f, 0.0f, 0.0f, 0.0f);
  }
};
AffineColumns columns_of(const Affine& a);

// Keep the mesh's own materials.
inline constexpr std::uint32_t kMeshMaterials = 0xffffffffu;

struct Instance {
  std::uint32_t mesh = 0;  // index into Scene::instanced_meshes
  Affine to_world;         // object -> world
  std::uint32_t material = kMeshMaterials;  // or every face's material
};

// The range of |n|^2 over a mesh's triangles, n the cross product of two edges (twice the
// area), in double; lo = +inf, hi = 0 without triangles.
struct AreaRange {
  double lo = HUGE_VAL, hi = 0.0;
};
AreaRange area_range(const Mesh& mesh);

// Whether every triangle of a mesh whose areas are `areas` keeps, placed by `a`, a normal that
// float arithmetic computes finite and not zero (the world triangle shading reads), with a
// margin of 2^28 either way: bounded through the largest and smallest stretch of `a`, at most
// its Frobenius norm and at least the inverse of its inverse's.
bool areas_fit_float(const AreaRange& areas, const Affine& a);

// The box in the world of `object` (a box in the mesh's coordinates) under `to_world`: the
// hull of its corners placed, in double, then widened by 2^-20 of its largest magnitude, beyond the
// rounding of the float transforms the traversal makes (a few ulps), so that a hit found
// in the mesh's coordinates lies inside it along the world ray.
Aabb world_box(const Aabb& object, const Affine& to_world);

}  // namespace rt2
