// rt2/scene/mesh.cpp — mesh bounds, concatenation, clean-up and transforms.
#include "rt2/scene/mesh.h"

#include "rt2/scene/instance.h"

#include <cmath>
#include <numbers>

namespace rt2 {

Aabb Mesh::bounds() const {
  Aabb b;
  for (const auto& f : faces)
    for (std::uint32_t i : f) b.grow(positions[i]);
  return b;
}

void Mesh::append(const Mesh& other) {
  const auto base = static_cast<std::uint32_t>(positions.size());
  // Per-vertex normals survive only if both parts have them; otherwise the result is flat.
  const bool smooth = (positions.empty() || !normals.empty()) &&
                      (other.positions.empty() || !other.normals.empty());
  // Texture coordinates survive if either part has them; the other part's vertices get (0, 0).
  if (!texcoords.empty() || !other.texcoords.empty()) {
    texcoords.resize(positions.size());
    if (other.texcoords.empty())
      texcoords.resize(positions.size() + other.positions.size());
    else
      texcoords.insert(texcoords.end(), other.texcoords.begin(), other.texcoords.end());
  }
  positions.insert(positions.end(), other.positions.begin(), other.positions.end());
  if (smooth)
    normals.insert(normals.end(), other.normals.begin(), other.normals.end());
  else
    normals.clear();
  for (const auto& f : other.faces) faces.push_back({f[0] + base, f[1] + base, f[2] + base});
  face_materials.insert(face_materials.end(), other.face_materials.begin(),
                        other.face_materials.end());
}

std::size_t Mesh::drop_degenerate() {
  std::size_t kept = 0;
  const std::size_t n = positions.size();
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const auto& f = faces[i];
    bool ok = f[0] < n && f[1] < n && f[2] < n;
    if (ok) {
      const vec4 c = cross(positions[f[1]] - positions[f[0]], positions[f[2]] - positions[f[0]]);
      const float a2 = dot(c, c);
      ok = a2 > 0.0f && std::isfinite(a2);
    }
    if (ok) {
      faces[kept] = f;
      face_materials[kept] = face_materials[i];
      ++kept;
    }
  }
  const std::size_t dropped = faces.size() - kept;
  faces.resize(kept);
  face_materials.resize(kept);
  return dropped;
}

AreaOutOfRange area_out_of_range(const Mesh& mesh) {
  AreaOutOfRange range;
  const std::size_t n = mesh.positions.size();
  for (const auto& f : mesh.faces) {
    if (f[0] >= n || f[1] >= n || f[2] >= n) continue;
    const vec4 &a = mesh.positions[f[0]], &b = mesh.positions[f[1]], &c = mesh.positions[f[2]];
    const vec4 cf = cross(b - a, c - a);
    const float a2 = dot(cf, cf);  // as drop_degenerate computes it
    if (a2 > 0.0f && std::isfinite(a2)) continue;
    const double ux = double(b[0]) - a[0], uy = double(b[1]) - a[1], uz = double(b[2]) - a[2];
    const double vx = double(c[0]) - a[0], vy = double(c[1]) - a[1], vz = double(c[2]) - a[2];
    const double x = uy * vz - uz * vy, y = uz * vx - ux * vz, z = ux * vy - uy * vx;
    const double d2 = x * x + y * y + z * z;
    if (!(d2 > 0.0) || !std::isfinite(d2)) continue;  // degenerate in double too
    if (std::isfinite(a2))
      ++range.too_small;
    else
      ++range.too_large;
  }
  return range;
}

void apply_transform(Mesh& mesh, const Transform& xf) {
  // In float, the rotation rounded from rotation_matrix's (instance.h): p R S + t.
  const auto rd = rotation_matrix(xf.rotate_degrees);
  float r[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r[i][j] = float(rd[std::size_t(i)][std::size_t(j)]);
  const auto apply = [&r](const vec4& v) {
    return vec4(r[0][0] * v[0] + r[0][1] * v[1] + r[0][2] * v[2],
                r[1][0] * v[0] + r[1][1] * v[1] + r[1][2] * v[2],
                r[2][0] * v[0] + r[2][1] * v[1] + r[2][2] * v[2]);
  };
  for (vec4& p : mesh.positions) p = apply(p * xf.scale) + xf.translate;
  // Normals: inverse transpose of R*S is R*S^-1 (R orthonormal).
  const vec4 inv_scale(1.0f / xf.scale[0], 1.0f / xf.scale[1], 1.0f / xf.scale[2]);
  for (vec4& n : mesh.normals) n = normalize(apply(n * inv_scale));
  // A reflection (odd number of negative scales) flips the winding; keep faces consistent.
  if (xf.scale[0] * xf.scale[1] * xf.scale[2] < 0.0f)
    for (auto& f : mesh.faces) std::swap(f[1], f[2]);
}

}  // namespace rt2
