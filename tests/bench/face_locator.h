// tests/bench/face_locator.h — which face of a mesh a hit point lies on, in double
// precision, independently of any ray tracing engine.
//
// bench_trace sees an engine's hit as a distance along a ray (rt2's primitive numbering is
// internal to its acceleration structure, Embree's is its own); to start secondary rays
// exactly on the surface and to tell why two engines disagree, it needs the face under the
// hit point. A uniform grid over the mesh bounds (about two cells per face) lists every face
// in each cell its slightly padded box overlaps; `nearest` returns the face of the point's
// cell closest to the point (Ericson, Real-Time Collision Detection, 5.1.5).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "rt2/scene/mesh.h"

namespace bench {

struct D3 {
  double x = 0, y = 0, z = 0;
  D3() = default;
  D3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
  explicit D3(const rt2::vec4& v) : x(v[0]), y(v[1]), z(v[2]) {}
  double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  rt2::vec4 to_vec4() const { return rt2::vec4(float(x), float(y), float(z)); }
};
inline D3 operator+(D3 a, D3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline D3 operator-(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline D3 operator*(double s, D3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline D3 cross(D3 a, D3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(D3 a) { return std::sqrt(dot(a, a)); }

// The point of triangle abc closest to p.
inline D3 closest_point_on_triangle(D3 p, D3 a, D3 b, D3 c) {
  const D3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const D3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + (d1 / (d1 - d3)) * ab;
  const D3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + (vb * denom) * ab + (vc * denom) * ac;
}

class FaceLocator {
 public:
  explicit FaceLocator(const rt2::Mesh& mesh) : mesh_(mesh) {
    for (const rt2::vec4& p : mesh.positions)
      for (int a = 0; a < 3; ++a) {
        lo_[a] = std::min(lo_[a], double(p[a]));
        hi_[a] = std::max(hi_[a], double(p[a]));
      }
    const double diag = std::sqrt((hi_[0] - lo_[0]) * (hi_[0] - lo_[0]) +
                                  (hi_[1] - lo_[1]) * (hi_[1] - lo_[1]) +
                                  (hi_[2] - lo_[2]) * (hi_[2] - lo_[2]));
    pad_ = 1e-5 * diag + 1e-30;
    // Cells of side s, about two per face.
    const double target = 2.0 * double(std::max<std::size_t>(1, mesh.faces.size()));
    double volume = 1.0;
    for (int a = 0; a < 3; ++a) volume *= std::max(hi_[a] - lo_[a], 1e-3 * diag + 1e-30);
    const double s = std::cbrt(volume / target);
    for (int a = 0; a < 3; ++a) {
      dims_[a] = std::clamp(int(std::ceil((hi_[a] - lo_[a]) / s)), 1, 1024);
      inv_cell_[a] = double(dims_[a]) / std::max(hi_[a] - lo_[a], 1e-30);
    }
    // Two passes: count the faces per cell, then fill (compressed rows).
    start_.assign(std::size_t(dims_[0]) * dims_[1] * dims_[2] + 1, 0);
    for (int pass = 0; pass < 2; ++pass) {
      if (pass == 1) {
        for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
        faces_.resize(start_.back());
        fill_ = std::vector<std::uint32_t>(start_.begin(), start_.end() - 1);
      }
      for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
        std::array<int, 3> c0, c1;
        for (int a = 0; a < 3; ++a) {
          double lo = mesh.positions[mesh.faces[f][0]][a], hi = lo;
          for (int k = 1; k < 3; ++k) {
            lo = std::min(lo, double(mesh.positions[mesh.faces[f][k]][a]));
            hi = std::max(hi, double(mesh.positions[mesh.faces[f][k]][a]));
          }
          c0[a] = cell(lo - pad_, a);
          c1[a] = cell(hi + pad_, a);
        }
        for (int z = c0[2]; z <= c1[2]; ++z)
          for (int y = c0[1]; y <= c1[1]; ++y)
            for (int x = c0[0]; x <= c1[0]; ++x) {
              const std::size_t c = index(x, y, z);
              if (pass == 0)
                ++start_[c + 1];
              else
                faces_[fill_[c]++] = f;
            }
      }
    }
  }

  struct Found {
    std::int64_t face = -1;  // -1: no face listed in the point's cell
    D3 point;                // the closest point of that face
    double distance = INFINITY;
  };

  // The face of p's cell closest to p.
  Found nearest(D3 p) const {
    Found best;
    const std::size_t c = index(cell(p.x, 0), cell(p.y, 1), cell(p.z, 2));
    for (std::uint32_t k = start_[c]; k < start_[c + 1]; ++k) {
      const std::uint32_t f = faces_[k];
      const D3 q = closest_point_on_triangle(p, vertex(f, 0), vertex(f, 1), vertex(f, 2));
      const double d = length(q - p);
      if (d < best.distance) best = {f, q, d};
    }
    return best;
  }

  D3 vertex(std::uint32_t face, int k) const {
    return D3(mesh_.positions[mesh_.faces[face][k]]);
  }

 private:
  int cell(double v, int a) const {
    return std::clamp(int(std::floor((v - lo_[a]) * inv_cell_[a])), 0, dims_[a] - 1);
  }
  std::size_t index(int x, int y, int z) const {
    return (std::size_t(z) * dims_[1] + y) * dims_[0] + x;
  }

  const rt2::Mesh& mesh_;
  double lo_[3] = {INFINITY, INFINITY, INFINITY}, hi_[3] = {-INFINITY, -INFINITY, -INFINITY};
  double pad_ = 0.0;
  double inv_cell_[3] = {};
  int dims_[3] = {1, 1, 1};
  std::vector<std::uint32_t> start_, faces_, fill_;
};

}  // namespace bench
