// rt2/scene/shapes.cpp — the procedural mesh generators of shapes.h.
//
// All generators emit through three helpers so winding and normals are decided once:
// add_grid (a rectangular grid of quads, used by box faces and the cylinder side),
// add_fan (a disc, used by the cylinder caps) and add_quad (used by the grid and the cube).
// The box and the cube share box_face, which orders each face's in-plane axes outward.
#include "rt2/scene/shapes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <string>
#include <unordered_map>
#include <vector>

#include "rt2/base/error.h"

namespace rt2 {
namespace {

struct Vertex {
  vec4 position;
  vec4 normal;
};

void require(bool ok, const std::string& message) {
  if (!ok) throw Error(message);
}

bool finite(const vec4& v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

// Face indices are 32-bit; refuse sizes whose vertex count would not fit.
void require_indexable(std::size_t vertices, const char* who) {
  require(vertices <= std::numeric_limits<std::uint32_t>::max(),
          std::string(who) + ": too many vertices for 32-bit indices (" + std::to_string(vertices) +
              ")");
}

// Exact at both ends (t = 0 gives a, t = 1 gives b), unlike a + (b - a) t, so generated
// boxes have exactly the requested bounds.
float lerp(float a, float b, float t) { return (1.0f - t) * a + t * b; }

vec4 unit_axis(int k, float sign) {
  vec4 v(0.0f, 0.0f, 0.0f);
  v[static_cast<std::size_t>(k)] = sign;
  return v;
}

Mesh named(const char* name) {
  Mesh m;
  m.name = name;
  return m;
}

std::uint32_t add_vertex(Mesh& m, const Vertex& v) {
  m.positions.push_back(v.position);
  m.normals.push_back(v.normal);
  return static_cast<std::uint32_t>(m.positions.size() - 1);
}

void add_triangle(Mesh& m, std::uint32_t a, std::uint32_t b, std::uint32_t c,
                  std::uint32_t material) {
  m.faces.push_back({a, b, c});
  m.face_materials.push_back(material);
}

// The quad a b c d (counter-clockwise seen from its front) as triangles a b c and a c d.
void add_quad(Mesh& m, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d,
              std::uint32_t material) {
  add_triangle(m, a, b, c, material);
  add_triangle(m, a, c, d, material);
}

// An (nu + 1) x (nv + 1) grid of vertices vertex_at(i, j) as nu x nv quads, 2 nu nv
// triangles. Quads run (i, j) (i+1, j) (i+1, j+1) (i, j+1), so the front side is the one
// cross(dP/di, dP/dj) points to.
template <class VertexAt>
void add_grid(Mesh& m, int nu, int nv, std::uint32_t material, VertexAt vertex_at) {
  const auto first = static_cast<std::uint32_t>(m.positions.size());
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) add_vertex(m, vertex_at(i, j));
  const auto row = static_cast<std::uint32_t>(nu + 1);
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      const std::uint32_t a =
          first + static_cast<std::uint32_t>(j) * row + static_cast<std::uint32_t>(i);
      add_quad(m, a, a + 1, a + 1 + row, a + row, material);
    }
  }
}

// A flat disc facing `normal`: a fan of ring.size() triangles around `center`, rim vertex k
// at center + ring[k] * radius. `ring` must run counter-clockwise about `normal`.
void add_fan(Mesh& m, const vec4& center, const vec4& normal, const std::vector<vec4>& ring,
             float radius, std::uint32_t material) {
  const std::uint32_t hub = add_vertex(m, {center, normal});
  for (const vec4& dir : ring) add_vertex(m, {center + dir * radius, normal});
  const auto n = static_cast<std::uint32_t>(ring.size());
  for (std::uint32_t k = 0; k < n; ++k)
    add_triangle(m, hub, hub + 1 + k, hub + 1 + (k + 1) % n, material);
}

// Face f (0..5) of an axis-aligned box: perpendicular to axis k, on the high side or not,
// with in-plane axes (a, b) ordered so that cross(e_a, e_b) points out of the box. For the
// cyclic order (k, k+1, k+2), cross(e_{k+1}, e_{k+2}) = e_k; the low face swaps them.
struct BoxFace {
  int k;
  bool high;
  int a, b;
};

BoxFace box_face(int f) {
  const int k = f / 2;
  const bool high = f % 2 == 1;
  const int p = (k + 1) % 3, q = (k + 2) % 3;
  return high ? BoxFace{k, true, p, q} : BoxFace{k, false, q, p};
}

// An orthonormal frame with cross(u, v) = w = axis, so angles measured from u towards v run
// counter-clockwise seen from the tip of the axis.
struct Frame {
  vec4 u, v, w;
};

Frame frame_around(const vec4& axis) {
  // Cross with the coordinate axis least aligned with `axis`, which is never near-parallel.
  const float ax = std::fabs(axis[0]), ay = std::fabs(axis[1]), az = std::fabs(axis[2]);
  const int least = ax <= ay && ax <= az ? 0 : (ay <= az ? 1 : 2);
  const vec4 u = normalize(cross(axis, unit_axis(least, 1.0f)));
  const vec4 v = cross(axis, u);
  return {u, v, axis};
}

// Unit directions at angles 2 pi k / segments in the frame's (u, v) plane.
std::vector<vec4> ring_directions(const Frame& f, int segments) {
  std::vector<vec4> ring;
  ring.reserve(static_cast<std::size_t>(segments));
  for (int k = 0; k < segments; ++k) {
    const float angle = 2.0f * std::numbers::pi_v<float> * float(k) / float(segments);
    ring.push_back(normalize(f.u * std::cos(angle) + f.v * std::sin(angle)));
  }
  return ring;
}

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  const auto lo = std::min(a, b), hi = std::max(a, b);
  return (std::uint64_t{lo} << 32) | hi;
}

// The unit icosahedron: the 12 vertices (0, ±1, ±phi) cyclically permuted, normalised, and
// 20 faces wound counter-clockwise seen from outside.
void unit_icosahedron(std::vector<vec4>& dirs, std::vector<std::array<std::uint32_t, 3>>& faces) {
  const float t = std::numbers::phi_v<float>;
  const float c[12][3] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                          {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                          {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (const auto& p : c) dirs.push_back(normalize(vec4(p[0], p[1], p[2])));
  // Five faces per row: the five around vertex 0, their neighbours, the five around vertex 3,
  // their neighbours.
  // clang-format off
  faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
           {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
           {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
           {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  // clang-format on
}

// Splits every face into four, pushing the new edge midpoints out to the unit sphere. A
// midpoint is made once per edge (looked up by its unordered vertex pair), so neighbouring
// faces share it and the mesh stays watertight; the corner order keeps the winding.
void subdivide(std::vector<vec4>& dirs, std::vector<std::array<std::uint32_t, 3>>& faces) {
  std::unordered_map<std::uint64_t, std::uint32_t> midpoints;
  auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
    const auto [it, inserted] =
        midpoints.try_emplace(edge_key(a, b), static_cast<std::uint32_t>(dirs.size()));
    if (inserted) dirs.push_back(normalize(dirs[a] + dirs[b]));
    return it->second;
  };
  std::vector<std::array<std::uint32_t, 3>> finer;
  finer.reserve(faces.size() * 4);
  for (const auto& [a, b, c] : faces) {
    const std::uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
    finer.push_back({a, ab, ca});
    finer.push_back({b, bc, ab});
    finer.push_back({c, ca, bc});
    finer.push_back({ab, bc, ca});
  }
  faces = std::move(finer);
}

}  // namespace

Mesh make_box(const vec4& lo, const vec4& hi, int subdivisions, std::uint32_t material) {
  require(finite(lo) && finite(hi), "make_box: corners must be finite");
  require(lo[0] < hi[0] && lo[1] < hi[1] && lo[2] < hi[2],
          "make_box: lo must be below hi in x, y and z, got lo " + mlib::str(lo) + " hi " +
              mlib::str(hi));
  require(subdivisions >= 1,
          "make_box: subdivisions must be >= 1, got " + std::to_string(subdivisions));
  const auto side = static_cast<std::size_t>(subdivisions) + 1;
  require_indexable(6 * side * side, "make_box");
  Mesh m = named("box");
  const float n = float(subdivisions);
  for (int f = 0; f < 6; ++f) {
    const BoxFace face = box_face(f);
    const auto k = static_cast<std::size_t>(face.k), a = static_cast<std::size_t>(face.a),
               b = static_cast<std::size_t>(face.b);
    const vec4 normal = unit_axis(face.k, face.high ? 1.0f : -1.0f);
    add_grid(m, subdivisions, subdivisions, material, [&](int i, int j) {
      vec4 p(0.0f, 0.0f, 0.0f);
      p[k] = face.high ? hi[k] : lo[k];
      p[a] = lerp(lo[a], hi[a], float(i) / n);
      p[b] = lerp(lo[b], hi[b], float(j) / n);
      return Vertex{p, normal};
    });
  }
  return m;
}

Mesh make_cylinder(const vec4& base_center, const vec4& axis, float radius, float height,
                   int segments, int rings, bool caps, std::uint32_t material) {
  require(finite(base_center), "make_cylinder: base_center must be finite");
  const float len2 = dot(axis, axis);
  require(std::fabs(len2 - 1.0f) < 1e-4f,
          "make_cylinder: axis must be a unit vector, got " + mlib::str(axis));
  require(std::isfinite(radius) && radius > 0.0f,
          "make_cylinder: radius must be > 0, got " + std::to_string(radius));
  require(std::isfinite(height) && height > 0.0f,
          "make_cylinder: height must be > 0, got " + std::to_string(height));
  require(segments >= 3, "make_cylinder: segments must be >= 3, got " + std::to_string(segments));
  require(rings >= 1, "make_cylinder: rings must be >= 1, got " + std::to_string(rings));
  const auto columns = static_cast<std::size_t>(segments) + 1;
  require_indexable(columns * (static_cast<std::size_t>(rings) + 1) + 2 * columns, "make_cylinder");

  Mesh m = named("cylinder");
  const Frame frame = frame_around(vec4(axis[0], axis[1], axis[2]));
  const std::vector<vec4> ring = ring_directions(frame, segments);
  // Side: i walks around (the last column reuses the first direction, so the seam closes
  // exactly), j walks up; cross(around, up) points outwards.
  add_grid(m, segments, rings, material, [&](int i, int j) {
    const vec4& dir = ring[static_cast<std::size_t>(i % segments)];
    const float h = lerp(0.0f, height, float(j) / float(rings));
    return Vertex{base_center + frame.w * h + dir * radius, dir};
  });
  if (caps) {
    // The ring runs counter-clockwise about +axis: right for the top cap; the bottom cap
    // faces -axis, so it takes the ring in the opposite order.
    add_fan(m, base_center + frame.w * height, frame.w, ring, radius, material);
    const std::vector<vec4> reversed(ring.rbegin(), ring.rend());
    add_fan(m, base_center, -frame.w, reversed, radius, material);
  }
  return m;
}

Mesh make_icosphere(const vec4& center, float radius, int subdivisions, std::uint32_t material) {
  require(finite(center), "make_icosphere: center must be finite");
  require(std::isfinite(radius) && radius > 0.0f,
          "make_icosphere: radius must be > 0, got " + std::to_string(radius));
  require(subdivisions >= 0 && subdivisions <= 10,
          "make_icosphere: subdivisions must be in [0, 10], got " + std::to_string(subdivisions));
  std::vector<vec4> dirs;
  std::vector<std::array<std::uint32_t, 3>> faces;
  unit_icosahedron(dirs, faces);
  for (int s = 0; s < subdivisions; ++s) subdivide(dirs, faces);

  Mesh m = named("icosphere");
  m.normals = dirs;
  m.positions.reserve(dirs.size());
  for (const vec4& d : dirs) m.positions.push_back(center + d * radius);
  m.faces = std::move(faces);
  m.face_materials.assign(m.faces.size(), material);
  return m;
}

Mesh make_cube(const vec4& center, float half_size, std::uint32_t material) {
  require(finite(center), "make_cube: center must be finite");
  require(std::isfinite(half_size) && half_size > 0.0f,
          "make_cube: half_size must be > 0, got " + std::to_string(half_size));
  Mesh m = named("cube");
  // Corner c (0..7) has bit k set when it is on the high side of axis k.
  for (unsigned c = 0; c < 8; ++c) {
    const vec4 sign(c & 1 ? 1.0f : -1.0f, c & 2 ? 1.0f : -1.0f, c & 4 ? 1.0f : -1.0f);
    add_vertex(m, {center + sign * half_size, normalize(sign)});
  }
  for (int f = 0; f < 6; ++f) {
    const BoxFace face = box_face(f);
    auto corner = [&](unsigned i, unsigned j) {
      return (face.high ? 1u : 0u) << face.k | i << face.a | j << face.b;
    };
    add_quad(m, corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1), material);
  }
  return m;
}

// Triangle budget (T = triangles; box 12 s^2, cylinder 2 seg (rings + 1) with caps,
// icosphere 20 * 4^s):
//   4 legs        cylinder 32 seg, 16 rings   4 * 2 * 32 * 17 = 4352
//   2 back posts  cylinder 32 seg, 20 rings   2 * 2 * 32 * 21 = 2688
//   4 stretchers  cylinder 16 seg,  4 rings   4 * 2 * 16 *  5 =  640
//   2 finials     icosphere s = 2             2 * 20 * 16     =  640
//   seat          box s = 12                  12 * 144        = 1728
//   back rail     box s = 4                   12 * 16         =  192
//   3 slats       box s = 4                   3 * 12 * 16     =  576
//                                                        total 10816
// The thesis's chair had 10,817, which no combination of these parts can give: each part
// is a closed surface, and a closed triangle mesh has 3 T = 2 E (every edge shared by two
// faces), so T is even — every count above is. 10,816 is the nearest.
Mesh make_chair(std::uint32_t material) {
  // Parts that meet overlap instead of touching: a joint is buried inside the part it joins
  // (legs, posts and slats end inside the seat or rail, at different depths; stretchers end at
  // leg centres), so no two faces are coplanar and coincident, which would make hits a tie.
  constexpr float kInset = 0.195f;     // legs and back posts at x, z = ±kInset
  constexpr float kSeatHalf = 0.225f;  // seat 0.45 x 0.45
  constexpr float kSeatBottom = 0.42f, kSeatTop = 0.45f;
  constexpr float kLegTop = 0.5f * (kSeatBottom + kSeatTop);
  constexpr float kPostBottom = kSeatBottom + 0.01f;
  constexpr float kPostTop = 0.92f;
  constexpr float kFinialRadius = 0.025f;
  constexpr float kRailBottom = 0.80f, kRailTop = 0.90f;
  // Half the rail's thickness in z; the slats are thinner so their faces stay inside it.
  constexpr float kRailHalf = 0.012f, kSlatHalf = 0.009f;
  const vec4 up(0.0f, 1.0f, 0.0f), along_x(1.0f, 0.0f, 0.0f), along_z(0.0f, 0.0f, 1.0f);

  Mesh chair = named("chair");
  for (float x : {-kInset, kInset}) {
    for (float z : {-kInset, kInset})
      chair.append(make_cylinder(vec4(x, 0.0f, z), up, 0.02f, kLegTop, 32, 16, true, material));
  }
  chair.append(make_box(vec4(-kSeatHalf, kSeatBottom, -kSeatHalf),
                        vec4(kSeatHalf, kSeatTop, kSeatHalf), 12, material));
  for (float x : {-kInset, kInset}) {
    chair.append(make_cylinder(vec4(x, kPostBottom, -kInset), up, 0.018f, kPostTop - kPostBottom,
                               32, 20, true, material));
    chair.append(make_icosphere(vec4(x, kPostTop + 0.6f * kFinialRadius, -kInset), kFinialRadius, 2,
                                material));
  }
  // The rail spans the post centres, so its ends are inside the posts.
  chair.append(make_box(vec4(-kInset, kRailBottom, -kInset - kRailHalf),
                        vec4(kInset, kRailTop, -kInset + kRailHalf), 4, material));
  const float slat_top = 0.5f * (kRailBottom + kRailTop);
  for (float x : {-0.09f, 0.0f, 0.09f})
    chair.append(make_box(vec4(x - 0.02f, kLegTop, -kInset - kSlatHalf),
                          vec4(x + 0.02f, slat_top, -kInset + kSlatHalf), 4, material));
  // Stretchers run from leg centre to leg centre: the side pair low, front and back higher,
  // so they do not cross.
  for (float x : {-kInset, kInset})
    chair.append(make_cylinder(vec4(x, 0.12f, -kInset), along_z, 0.012f, 2.0f * kInset, 16, 4, true,
                               material));
  for (float z : {-kInset, kInset})
    chair.append(make_cylinder(vec4(-kInset, 0.18f, z), along_x, 0.012f, 2.0f * kInset, 16, 4, true,
                               material));
  return chair;
}

}  // namespace rt2
