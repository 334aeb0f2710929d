// rt2/scene/instance.cpp — affine transforms of instances (see instance.h).
#include "rt2/scene/instance.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rt2 {

double Affine::determinant() const {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
         m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

bool Affine::is_identity() const { return m == Affine{}.m; }

bool Affine::finite() const {
  for (const auto& row : m)
    for (double x : row)
      if (!std::isfinite(x)) return false;
  return true;
}

Affine Affine::inverse() const {
  const auto& a = m;
  // The adjugate (transposed cofactors) over the determinant, expanded along the first row.
  const double c00 = a[1][1] * a[2][2] - a[1][2] * a[2][1];
  const double c01 = a[1][2] * a[2][0] - a[1][0] * a[2][2];
  const double c02 = a[1][0] * a[2][1] - a[1][1] * a[2][0];
  const double inv = 1.0 / (a[0][0] * c00 + a[0][1] * c01 + a[0][2] * c02);
  Affine r;
  r.m[0] = {c00 * inv, (a[0][2] * a[2][1] - a[0][1] * a[2][2]) * inv,
            (a[0][1] * a[1][2] - a[0][2] * a[1][1]) * inv, 0.0};
  r.m[1] = {c01 * inv, (a[0][0] * a[2][2] - a[0][2] * a[2][0]) * inv,
            (a[0][2] * a[1][0] - a[0][0] * a[1][2]) * inv, 0.0};
  r.m[2] = {c02 * inv, (a[0][1] * a[2][0] - a[0][0] * a[2][1]) * inv,
            (a[0][0] * a[1][1] - a[0][1] * a[1][0]) * inv, 0.0};
  for (std::size_t i = 0; i < 3; ++i)
    r.m[i][3] = -(r.m[i][0] * a[0][3] + r.m[i][1] * a[1][3] + r.m[i][2] * a[2][3]);
  return r;
}

std::array<double, 3> Affine::point(const std::array<double, 3>& p) const {
  std::array<double, 3> q;
  for (int i = 0; i < 3; ++i) q[i] = m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2] + m[i][3];
  return q;
}

std::array<std::array<double, 3>, 3> rotation_matrix(const vec4& degrees) {
  const double k = std::numbers::pi / 180.0;
  const double cx = std::cos(degrees[0] * k), sx = std::sin(degrees[0] * k);
  const double cy = std::cos(degrees[1] * k), sy = std::sin(degrees[1] * k);
  const double cz = std::cos(degrees[2] * k), sz = std::sin(degrees[2] * k);
  return {{{cz * cy, cz * sy * sx - sz * cx, cz * sy * cx + sz * sx},
           {sz * cy, sz * sy * sx + cz * cx, sz * sy * cx - cz * sx},
           {-sy, cy * sx, cy * cx}}};
}

Affine affine_of(const Transform& xf) {
  const auto r = rotation_matrix(xf.rotate_degrees);
  Affine a;
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t j = 0; j < 3; ++j) a.m[i][j] = r[i][j] * xf.scale[int(j)];
    a.m[i][3] = xf.translate[int(i)];
  }
  return a;
}

AffineColumns columns_of(const Affine& a) {
  AffineColumns c;
  for (int j = 0; j < 4; ++j)
    c.c[j] = vec4(float(a.m[0][j]), float(a.m[1][j]), float(a.m[2][j]), 0.0f);
  return c;
}

AreaRange area_range(const Mesh& mesh) {
  AreaRange r;
  for (const auto& f : mesh.faces) {
    const vec4 &a = mesh.positions[f[0]], &b = mesh.positions[f[1]], &c = mesh.positions[f[2]];
    const double ux = double(b[0]) - a[0], uy = double(b[1]) - a[1], uz = double(b[2]) - a[2];
    const double vx = double(c[0]) - a[0], vy = double(c[1]) - a[1], vz = double(c[2]) - a[2];
    const double x = uy * vz - uz * vy, y = uz * vx - ux * vz, z = ux * vy - uy * vx;
    const double n2 = x * x + y * y + z * z;
    r.lo = std::min(r.lo, n2);
    r.hi = std::max(r.hi, n2);
  }
  return r;
}

namespace {

double frobenius(const Affine& a) {
  double s = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) s += a.m[std::size_t(i)][std::size_t(j)] * a.m[std::size_t(i)][std::size_t(j)];
  return std::sqrt(s);
}

}  // namespace

bool areas_fit_float(const AreaRange& areas, const Affine& a) {
  if (areas.hi == 0.0) return true;  // no triangles
  // |cof(A) n| lies between s_min^2 |n| and s_max^2 |n|.
  const double s_max = frobenius(a), s_min = 1.0 / frobenius(a.inverse());
  const double hi = areas.hi * std::pow(s_max, 4.0), lo = areas.lo * std::pow(s_min, 4.0);
  return std::isfinite(hi) && hi <= 0x1p100 && lo >= 0x1p-100;
}

Aabb world_box(const Aabb& object, const Affine& to_world) {
  // The box's centre placed, and its half extents through |A| (Arvo 1990): the hull of the
  // placed corners.
  double lo[3], hi[3], mag = 0.0;
  for (std::size_t i = 0; i < 3; ++i) {
    const auto& row = to_world.m[i];
    double c = row[3], e = 0.0;
    for (std::size_t j = 0; j < 3; ++j) {
      const double centre = 0.5 * (double(object.lo[int(j)]) + object.hi[int(j)]);
      const double half = 0.5 * (double(object.hi[int(j)]) - object.lo[int(j)]);
      c += row[j] * centre;
      e += std::fabs(row[j]) * half;
    }
    lo[i] = c - e;
    hi[i] = c + e;
    mag = std::max({mag, std::fabs(lo[i]), std::fabs(hi[i])});
  }
  const double pad = mag * 0x1p-20;
  Aabb b;
  b.lo = vec4(float(lo[0] - pad), float(lo[1] - pad), float(lo[2] - pad));
  b.hi = vec4(float(hi[0] + pad), float(hi[1] + pad), float(hi[2] + pad));
  return b;
}

}  // namespace rt2
