// rt2/scene/shapes.h: the procedural meshes. Each test names the property it checks: triangle
// counts follow the documented formulas, normals are unit length, no face is degenerate,
// closed meshes are watertight and outward facing, bounds are exact, and the chair is a
// chair-sized object of the thesis's size standing on the ground.
#include "rt2/scene/shapes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "rt2/base/error.h"

namespace rt2 {
namespace {

constexpr std::uint32_t kMaterial = 7;

std::size_t degenerate_faces(Mesh m) { return m.drop_degenerate(); }

bool normals_are_unit(const Mesh& m) {
  if (m.normals.size() != m.positions.size()) return false;
  for (const vec4& n : m.normals)
    if (std::fabs(std::sqrt(float(dot(n, n))) - 1.0f) > 1e-5f) return false;
  return true;
}

// Every directed edge (a, b) appears exactly once and its reverse (b, a) exactly once.
bool closed_and_watertight(const Mesh& m) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (const auto& f : m.faces)
    for (int k = 0; k < 3; ++k) ++directed[{f[k], f[(k + 1) % 3]}];
  for (const auto& [edge, count] : directed) {
    const auto reverse = directed.find({edge.second, edge.first});
    if (count != 1 || reverse == directed.end() || reverse->second != 1) return false;
  }
  return !m.faces.empty();
}

// Divergence theorem: the volume is the sum over faces of p0 · (p1 x p2) / 6, positive when
// every face is wound counter-clockwise seen from outside.
double signed_volume(const Mesh& m) {
  double v = 0.0;
  for (const auto& f : m.faces) {
    const vec4 c = cross(m.positions[f[1]], m.positions[f[2]]);
    for (int k = 0; k < 3; ++k) v += double(m.positions[f[0]][k]) * double(c[k]);
  }
  return v / 6.0;
}

vec4 face_normal(const Mesh& m, const std::array<std::uint32_t, 3>& f) {
  return cross(m.positions[f[1]] - m.positions[f[0]], m.positions[f[2]] - m.positions[f[0]]);
}

vec4 face_centroid(const Mesh& m, const std::array<std::uint32_t, 3>& f) {
  return (m.positions[f[0]] + m.positions[f[1]] + m.positions[f[2]]) * (1.0f / 3.0f);
}

std::vector<Mesh> one_of_each() {
  return {make_box(vec4(-1, -2, -3), vec4(1, 0.5f, 2), 3, kMaterial),
          make_cylinder(vec4(0.1f, 0.2f, 0.3f), normalize(vec4(1, 2, 3)), 0.5f, 2.0f, 24, 5, true,
                        kMaterial),
          make_icosphere(vec4(1, -1, 2), 0.75f, 3, kMaterial),
          make_cube(vec4(-1, 2, 0.5f), 0.3f, kMaterial), make_chair(kMaterial)};
}

TEST(Shapes, BoxHas12SubdivisionsSquaredTriangles) {
  for (int s : {1, 2, 5, 12}) {
    const Mesh m = make_box(vec4(0, 0, 0), vec4(1, 2, 3), s, kMaterial);
    EXPECT_EQ(m.triangle_count(), std::size_t(12 * s * s)) << "subdivisions " << s;
    EXPECT_EQ(m.positions.size(), std::size_t(6 * (s + 1) * (s + 1)));
  }
}

TEST(Shapes, CylinderHas2SegmentsTimesRingsPlusCapsTriangles) {
  for (bool caps : {false, true}) {
    for (auto [segments, rings] : {std::pair{3, 1}, {16, 4}, {32, 17}}) {
      const Mesh m =
          make_cylinder(vec4(0, 0, 0), vec4(0, 1, 0), 1.0f, 2.0f, segments, rings, caps, kMaterial);
      EXPECT_EQ(m.triangle_count(), std::size_t(2 * segments * (rings + (caps ? 1 : 0))))
          << segments << " segments, " << rings << " rings, caps " << caps;
    }
  }
}

TEST(Shapes, IcosphereHas20Times4PowSubdivisionsTriangles) {
  std::size_t pow4 = 1;
  for (int s = 0; s <= 4; ++s, pow4 *= 4) {
    const Mesh m = make_icosphere(vec4(0, 0, 0), 1.0f, s, kMaterial);
    EXPECT_EQ(m.triangle_count(), 20 * pow4) << "subdivisions " << s;
    EXPECT_EQ(m.positions.size(), 10 * pow4 + 2) << "subdivisions " << s;
  }
}

TEST(Shapes, CubeHas8VerticesAnd12Triangles) {
  const Mesh m = make_cube(vec4(0, 0, 0), 1.0f, kMaterial);
  EXPECT_EQ(m.positions.size(), 8u);
  EXPECT_EQ(m.triangle_count(), 12u);
}

TEST(Shapes, EveryVertexHasAUnitNormal) {
  for (const Mesh& m : one_of_each()) EXPECT_TRUE(normals_are_unit(m)) << m.name;
}

TEST(Shapes, EveryFaceHasTheGivenMaterial) {
  for (const Mesh& m : one_of_each()) {
    ASSERT_EQ(m.face_materials.size(), m.faces.size()) << m.name;
    for (std::uint32_t mat : m.face_materials) ASSERT_EQ(mat, kMaterial) << m.name;
  }
}

TEST(Shapes, NoGeneratorMakesDegenerateFaces) {
  for (const Mesh& m : one_of_each()) EXPECT_EQ(degenerate_faces(m), 0u) << m.name;
  // Fine tessellations of small shapes are where faces would collapse first.
  EXPECT_EQ(degenerate_faces(make_icosphere(vec4(0, 0, 0), 1e-3f, 6, kMaterial)), 0u);
  EXPECT_EQ(degenerate_faces(make_cylinder(vec4(0, 0, 0), vec4(0, 0, 1), 1e-3f, 1e-3f, 256, 64,
                                           true, kMaterial)),
            0u);
}

TEST(Shapes, IcosphereIsClosedAndWatertight) {
  for (int s = 0; s <= 4; ++s)
    EXPECT_TRUE(closed_and_watertight(make_icosphere(vec4(0.5f, 0, -1), 2.0f, s, kMaterial)))
        << "subdivisions " << s;
}

TEST(Shapes, CubeIsClosedAndWatertight) {
  EXPECT_TRUE(closed_and_watertight(make_cube(vec4(1, 2, 3), 0.5f, kMaterial)));
}

TEST(Shapes, ClosedMeshesHavePositiveSignedVolume) {
  const float r = 1.5f;
  const double ico = signed_volume(make_icosphere(vec4(0.5f, -1, 2), r, 4, kMaterial));
  const double ball = 4.0 / 3.0 * std::acos(-1.0) * r * r * r;
  EXPECT_GT(ico, 0.99 * ball);  // inscribed: a little less than the ball
  EXPECT_LT(ico, ball);
  EXPECT_NEAR(signed_volume(make_cube(vec4(-2, 1, 3), 0.5f, kMaterial)), 1.0, 1e-5);
  // A box is closed geometrically though its faces do not share vertices.
  EXPECT_NEAR(signed_volume(make_box(vec4(-1, 0, 1), vec4(2, 1, 3), 4, kMaterial)), 6.0, 1e-4);
}

TEST(Shapes, BoxFacesPointAwayFromTheCentre) {
  const vec4 lo(-1, -2, 0.5f), hi(3, 1, 2);
  const Mesh m = make_box(lo, hi, 3, kMaterial);
  const vec4 centre = (lo + hi) * 0.5f;
  for (const auto& f : m.faces) {
    const vec4 n = face_normal(m, f);
    ASSERT_GT(float(dot(n, face_centroid(m, f) - centre)), 0.0f);
    // Flat shading: each vertex normal is the face's own normal.
    for (std::uint32_t i : f) ASSERT_GT(float(dot(normalize(n), m.normals[i])), 0.99999f);
  }
}

TEST(Shapes, CylinderFacesPointAwayFromTheAxis) {
  const vec4 base(1, 2, 3), axis = normalize(vec4(-1, 0.5f, 2));
  const Mesh m = make_cylinder(base, axis, 0.4f, 1.5f, 20, 3, true, kMaterial);
  const vec4 centre = base + axis * 0.75f;
  for (const auto& f : m.faces) {
    const vec4 n = face_normal(m, f);
    ASSERT_GT(float(dot(n, face_centroid(m, f) - centre)), 0.0f);
    for (std::uint32_t i : f) ASSERT_GT(float(dot(n, m.normals[i])), 0.0f);
  }
}

TEST(Shapes, IcosphereVerticesLieAtTheRadius) {
  const vec4 centre(0.25f, -0.5f, 1.0f);
  const double r = 2.0;
  const Mesh m = make_icosphere(centre, float(r), 5, kMaterial);
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double d = double(m.positions[i][k]) - double(centre[k]);
      d2 += d * d;
    }
    ASSERT_NEAR(std::sqrt(d2), r, 1e-6 * r) << "vertex " << i;
    // Radial normals.
    ASSERT_GT(float(dot(normalize(m.positions[i] - centre), m.normals[i])), 0.99999f);
  }
}

TEST(Shapes, BoxBoundsEqualLoAndHi) {
  const vec4 lo(-0.225f, 0.42f, -0.225f), hi(0.225f, 0.45f, 0.225f);
  for (int s : {1, 3, 12}) {
    const Aabb b = make_box(lo, hi, s, kMaterial).bounds();
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(b.lo[k], lo[k]) << "axis " << k;
      EXPECT_EQ(b.hi[k], hi[k]) << "axis " << k;
    }
  }
}

TEST(Shapes, CylinderBoundsAreRadiusAroundAndHeightAlong) {
  const float r = 0.3f, h = 1.25f;
  const Aabb up =
      make_cylinder(vec4(1, 0, 2), vec4(0, 1, 0), r, h, 32, 4, true, kMaterial).bounds();
  EXPECT_NEAR(up.lo[0], 1 - r, 1e-6f);
  EXPECT_NEAR(up.hi[0], 1 + r, 1e-6f);
  EXPECT_NEAR(up.lo[2], 2 - r, 1e-6f);
  EXPECT_NEAR(up.hi[2], 2 + r, 1e-6f);
  EXPECT_EQ(up.lo[1], 0.0f);
  EXPECT_EQ(up.hi[1], h);
  const Aabb side =
      make_cylinder(vec4(0, 0, 0), vec4(-1, 0, 0), r, h, 16, 1, false, kMaterial).bounds();
  EXPECT_NEAR(side.lo[0], -h, 1e-6f);
  EXPECT_NEAR(side.hi[0], 0.0f, 1e-6f);
  for (int k : {1, 2}) {
    EXPECT_NEAR(side.lo[k], -r, 1e-6f);
    EXPECT_NEAR(side.hi[k], r, 1e-6f);
  }
}

TEST(Shapes, InvalidArgumentsThrowError) {
  const vec4 o(0, 0, 0), y(0, 1, 0);
  EXPECT_THROW(make_box(o, vec4(1, 1, 1), 0, 0), Error);
  EXPECT_THROW(make_box(vec4(1, 0, 0), vec4(1, 1, 1), 1, 0), Error);  // flat in x
  EXPECT_THROW(make_cylinder(o, y, 0.0f, 1.0f, 8, 1, true, 0), Error);
  EXPECT_THROW(make_cylinder(o, y, 1.0f, -1.0f, 8, 1, true, 0), Error);
  EXPECT_THROW(make_cylinder(o, y, 1.0f, 1.0f, 2, 1, true, 0), Error);
  EXPECT_THROW(make_cylinder(o, y, 1.0f, 1.0f, 8, 0, true, 0), Error);
  EXPECT_THROW(make_cylinder(o, vec4(0, 2, 0), 1.0f, 1.0f, 8, 1, true, 0), Error);
  EXPECT_THROW(make_cylinder(o, y, std::nanf(""), 1.0f, 8, 1, true, 0), Error);
  EXPECT_THROW(make_icosphere(o, -1.0f, 1, 0), Error);
  EXPECT_THROW(make_icosphere(o, 1.0f, -1, 0), Error);
  EXPECT_THROW(make_icosphere(o, 1.0f, 11, 0), Error);
  EXPECT_THROW(make_cube(o, 0.0f, 0), Error);
}

TEST(Shapes, ChairHasTheDocumentedTriangleCount) {
  const Mesh chair = make_chair(kMaterial);
  EXPECT_GE(chair.triangle_count(), 10000u);
  EXPECT_LE(chair.triangle_count(), 11000u);
  EXPECT_EQ(chair.triangle_count(), 10816u);  // shapes.cpp: the thesis's 10,817 is odd
}

TEST(Shapes, ChairStandsOnTheGround) {
  const Aabb b = make_chair(kMaterial).bounds();
  EXPECT_NEAR(b.lo[1], 0.0f, 1e-6f);
}

TEST(Shapes, ChairFitsInAOneMetreBoxCentredOnTheYAxis) {
  const Aabb b = make_chair(kMaterial).bounds();
  for (int k = 0; k < 3; ++k) EXPECT_LE(b.extent()[k], 1.0f) << "axis " << k;
  EXPECT_NEAR(b.lo[0], -b.hi[0], 1e-6f);  // symmetric left to right
  EXPECT_GT(b.hi[1], 0.9f);               // the back reaches ~0.95
  EXPECT_LT(b.hi[1], 1.0f);
}

TEST(Shapes, ChairSeatIsAtSeatHeightAndTheBackAtMinusZ) {
  const Mesh chair = make_chair(kMaterial);
  // Above the seat (y > 0.46) everything belongs to the back, behind the seat's middle.
  for (const vec4& p : chair.positions) ASSERT_TRUE(p[1] <= 0.46f || p[2] < -0.15f) << mlib::str(p);
  // A vertical ray down through the middle of the seat meets its top at y = 0.45.
  float top = 0.0f;
  for (const vec4& p : chair.positions)
    if (std::fabs(p[0]) < 0.1f && std::fabs(p[2]) < 0.1f) top = std::max(top, p[1]);
  EXPECT_FLOAT_EQ(top, 0.45f);
}

TEST(Shapes, ChairHasNoDegenerateFaces) { EXPECT_EQ(degenerate_faces(make_chair(kMaterial)), 0u); }

}  // namespace
}  // namespace rt2
