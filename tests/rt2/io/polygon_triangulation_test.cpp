// tests/rt2/io/polygon_triangulation_test.cpp — rt2::io::PolygonTriangulator against oracles: a
// polygon of n corners gives n − 2 triangles; for a simple polygon (also one with holes joined
// by bridge edges) every triangle has the polygon's winding, lies inside it, and their areas
// add up to the polygon's; quads are split as tinyobjloader splits them unless that diagonal
// is outside; garbage neither crashes nor takes more than near-linear work.
#include "rt2/io/polygon_triangulation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "tests/rt2/test_util.h"

namespace rt2::io {
namespace {

constexpr double kPi = std::numbers::pi;

using Polygon = std::vector<vec4>;

// Twice the signed area of the polygon in the xy plane (counter-clockwise positive).
double twice_area(const Polygon& p) {
  double s = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const vec4& a = p[i];
    const vec4& b = p[(i + 1) % p.size()];
    s += double(a[0]) * b[1] - double(b[0]) * a[1];
  }
  return s;
}

double twice_area(const vec4& a, const vec4& b, const vec4& c) {
  return (double(b[0]) - a[0]) * (double(c[1]) - a[1]) -
         (double(b[1]) - a[1]) * (double(c[0]) - a[0]);
}

// Even-odd rule: an edge walked twice (a bridge) crosses twice, so it does not count.
bool inside(const Polygon& p, double x, double y) {
  bool in = false;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
    const double xi = p[i][0], yi = p[i][1], xj = p[j][0], yj = p[j][1];
    if ((yi > y) != (yj > y) && x < (xj - xi) * (y - yi) / (yj - yi) + xi) in = !in;
  }
  return in;
}

std::vector<CornerTriangle> triangulate(const Polygon& p, bool* complete = nullptr,
                                        std::size_t* work = nullptr) {
  PolygonTriangulator t;
  std::vector<CornerTriangle> out;
  const bool ok = t.triangulate(p, out);
  if (complete) *complete = ok;
  if (work) *work = t.last_work();
  return out;
}

// The oracle for a simple polygon (holes joined by bridges allowed) in the xy plane, wound
// counter-clockwise: n − 2 triangles, none clockwise, each non-degenerate one's centroid
// inside, areas summing to the polygon's.
void expect_exact_triangulation(const Polygon& p, const char* what) {
  SCOPED_TRACE(what);
  bool complete = false;
  const std::vector<CornerTriangle> tris = triangulate(p, &complete);
  EXPECT_TRUE(complete);
  ASSERT_EQ(tris.size(), p.size() - 2);
  double sum = 0.0;
  std::size_t outside = 0, clockwise = 0;
  for (const CornerTriangle& t : tris) {
    ASSERT_LT(t[0], p.size());
    ASSERT_LT(t[1], p.size());
    ASSERT_LT(t[2], p.size());
    const vec4 &a = p[t[0]], &b = p[t[1]], &c = p[t[2]];
    const double area = twice_area(a, b, c);
    sum += area;
    clockwise += area < 0.0;
    if (area > 0.0) {
      const double cx = (double(a[0]) + b[0] + c[0]) / 3, cy = (double(a[1]) + b[1] + c[1]) / 3;
      outside += !inside(p, cx, cy);
    }
  }
  EXPECT_EQ(clockwise, 0u);
  EXPECT_EQ(outside, 0u);
  const double expected = twice_area(p);
  EXPECT_NEAR(sum, expected, 1e-9 * std::fabs(expected) + 1e-12);
}

Polygon regular(std::size_t n, double r = 1.0, double phase = 0.0) {
  Polygon p;
  for (std::size_t k = 0; k < n; ++k) {
    const double a = 2 * kPi * double(k) / double(n) + phase;
    p.emplace_back(float(r * std::cos(a)), float(r * std::sin(a)), 0.0f);
  }
  return p;
}

// Alternating radii 1 and `inner`: half the corners reflex.
Polygon star(std::size_t n, double inner = 0.8) {
  Polygon p = regular(n);
  for (std::size_t k = 1; k < n; k += 2) p[k] = p[k] * float(inner);
  return p;
}

// Random radii at sorted random angles: star-shaped about the origin, hence simple.
Polygon random_star(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> angle(0.0, 2 * kPi), radius(0.1, 1.0);
  std::vector<double> angles(n);
  for (double& a : angles) a = angle(rng);
  std::sort(angles.begin(), angles.end());
  Polygon p;
  for (const double a : angles) {
    const double r = radius(rng);
    p.emplace_back(float(r * std::cos(a)), float(r * std::sin(a)), 0.0f);
  }
  return p;
}

// A comb: `teeth` teeth of width 1 and height 5 on a base of height 1, gaps of width 1.
Polygon comb(int teeth) {
  Polygon p{vec4(0, 0, 0), vec4(float(2 * teeth - 1), 0, 0)};
  for (int t = teeth - 1; t >= 0; --t) {
    const float x = float(2 * t);
    p.emplace_back(x + 1, 6, 0);
    p.emplace_back(x, 6, 0);
    if (t > 0) {
      p.emplace_back(x, 1, 0);
      p.emplace_back(x - 1, 1, 0);
    }
  }
  return p;
}

// A band along an Archimedean spiral, `turns` turns, `n` corners on each side.
Polygon spiral(std::size_t n, double turns) {
  Polygon outer, inner;
  for (std::size_t k = 0; k < n; ++k) {
    const double t = 2 * kPi * turns * double(k) / double(n - 1);
    const double r = 1.0 + t / (2 * kPi);
    outer.emplace_back(float((r + 0.5) * std::cos(t)), float((r + 0.5) * std::sin(t)), 0.0f);
    inner.emplace_back(float(r * std::cos(t)), float(r * std::sin(t)), 0.0f);
  }
  Polygon p(outer.begin(), outer.end());
  p.insert(p.end(), inner.rbegin(), inner.rend());
  if (twice_area(p) < 0) std::reverse(p.begin(), p.end());
  return p;
}

// `outer` (counter-clockwise) with `hole` (counter-clockwise, inside it) joined by a bridge
// from outer[0] to hole[0], as LightWave writes it: outer, outer[0] again, the hole walked
// clockwise from hole[0] back to hole[0], then back along the bridge.
Polygon bridged(const Polygon& outer, const Polygon& hole) {
  Polygon p = outer;
  p.push_back(outer[0]);
  p.push_back(hole[0]);
  for (std::size_t k = hole.size() - 1; k > 0; --k) p.push_back(hole[k]);
  p.push_back(hole[0]);
  return p;
}

Polygon square(float x0, float y0, float x1, float y1) {
  return {vec4(x0, y0, 0), vec4(x1, y0, 0), vec4(x1, y1, 0), vec4(x0, y1, 0)};
}

TEST(PolygonTriangulation, ConvexPolygonsAreTriangulatedExactly) {
  for (std::size_t n : {5u, 6u, 7u, 8u, 16u, 31u, 64u, 100u, 1000u})
    expect_exact_triangulation(regular(n, 1.0, 0.1), "regular");
}

TEST(PolygonTriangulation, ConcavePolygonsAreTriangulatedExactly) {
  expect_exact_triangulation(star(10), "star 10");
  expect_exact_triangulation(star(1000, 0.3), "star 1000");
  for (unsigned seed = 1; seed <= 20; ++seed)
    expect_exact_triangulation(random_star(5 + seed * 37, seed), "random star");
  expect_exact_triangulation(comb(50), "comb");
  expect_exact_triangulation(spiral(400, 3.0), "spiral");
  // An L and a U: reflex corners next to each other.
  expect_exact_triangulation(
      {vec4(0, 0, 0), vec4(2, 0, 0), vec4(2, 1, 0), vec4(1, 1, 0), vec4(1, 2, 0), vec4(0, 2, 0)},
      "L");
  expect_exact_triangulation({vec4(0, 0, 0), vec4(3, 0, 0), vec4(3, 3, 0), vec4(2, 3, 0),
                              vec4(2, 1, 0), vec4(1, 1, 0), vec4(1, 3, 0), vec4(0, 3, 0)},
                             "U");
}

TEST(PolygonTriangulation, HolesJoinedByABridgeEdgeStayHoles) {
  // The square frame (a broken fan before) and a LightWave ring (a filled disc before).
  expect_exact_triangulation(bridged(square(0, 0, 4, 4), square(1, 1, 3, 3)), "square frame");
  expect_exact_triangulation(bridged(regular(32), regular(32, 0.93)), "ring");
  expect_exact_triangulation(bridged(regular(64, 1.0, 0.05), regular(17, 0.2, 0.3)), "small hole");
  // The bridge to another corner of the hole, touching it only there.
  expect_exact_triangulation(
      bridged(square(0, 0, 4, 4), {vec4(1, 3, 0), vec4(1, 1, 0), vec4(3, 1, 0), vec4(3, 3, 0)}),
      "bridge to another corner");
  // Two holes, each with its own bridge from the outer boundary.
  const Polygon once = bridged(square(0, 0, 10, 4), square(1, 1, 3, 3));
  Polygon twice = bridged(once, square(6, 1, 8, 3));
  expect_exact_triangulation(twice, "two holes");
}

TEST(PolygonTriangulation, RepeatedAndCollinearCornersKeepTheArea) {
  // A midpoint on every side, and a corner written twice: some triangles have zero area.
  expect_exact_triangulation({vec4(0, 0, 0), vec4(1, 0, 0), vec4(2, 0, 0), vec4(2, 1, 0),
                              vec4(2, 2, 0), vec4(1, 2, 0), vec4(0, 2, 0), vec4(0, 1, 0)},
                             "midpoints");
  expect_exact_triangulation(
      {vec4(0, 0, 0), vec4(2, 0, 0), vec4(2, 0, 0), vec4(2, 2, 0), vec4(1, 3, 0), vec4(0, 2, 0)},
      "repeated corner");
}

// Every triangle's normal points the way the polygon's does, in any plane and either winding.
TEST(PolygonTriangulation, TrianglesKeepThePolygonsWinding) {
  const Polygon base = star(40, 0.5);
  for (int axis = 0; axis < 3; ++axis) {
    for (const bool reversed : {false, true}) {
      Polygon p;
      for (const vec4& v : base) {
        const float c[3] = {v[0], v[1], 0.25f};  // off the origin
        p.emplace_back(c[(3 - axis) % 3], c[(4 - axis) % 3], c[(5 - axis) % 3]);
      }
      if (reversed) std::reverse(p.begin(), p.end());
      vec4 n(0, 0, 0);
      for (std::size_t i = 0; i < p.size(); ++i) n += cross(p[i], p[(i + 1) % p.size()]);
      const std::vector<CornerTriangle> tris = triangulate(p);
      ASSERT_EQ(tris.size(), p.size() - 2);
      for (const CornerTriangle& t : tris)
        EXPECT_GT(float(dot(cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]), n)), 0.0f)
            << "axis " << axis << (reversed ? " reversed" : "");
    }
  }
}

TEST(PolygonTriangulation, ConvexQuadsAreSplitAlongTheShorterDiagonal) {
  // 0-2 shorter: (0,1,2), (0,2,3); 1-3 shorter: (0,1,3), (1,2,3), as tinyobjloader splits.
  const Polygon short02{vec4(2, -1, 0), vec4(4, 0, 0), vec4(2, 1, 0), vec4(0, 0, 0)};
  const Polygon short13{vec4(0, 0, 0), vec4(2, -1, 0), vec4(4, 0, 0), vec4(2, 1, 0)};
  EXPECT_EQ(triangulate(short02), (std::vector<CornerTriangle>{{0, 1, 2}, {0, 2, 3}}));
  EXPECT_EQ(triangulate(short13), (std::vector<CornerTriangle>{{0, 1, 3}, {1, 2, 3}}));
  const Polygon square_xz{vec4(0, 0, 0), vec4(0, 0, 1), vec4(1, 0, 1), vec4(1, 0, 0)};
  EXPECT_EQ(triangulate(square_xz), (std::vector<CornerTriangle>{{0, 1, 3}, {1, 2, 3}}));  // a tie
}

TEST(PolygonTriangulation, ConcaveQuadsAreSplitThroughTheReflexCorner) {
  // A dart with its reflex corner at 1 or at 2; the diagonal through it is the longer one,
  // which tinyobjloader does not take.
  const Polygon reflex_1{vec4(0, 0, 0), vec4(1, 0.2f, 0), vec4(2, 0, 0), vec4(1, 3, 0)};
  const Polygon reflex_2{vec4(1, 3, 0), vec4(0, 0, 0), vec4(1, 0.2f, 0), vec4(2, 0, 0)};
  EXPECT_EQ(triangulate(reflex_1), (std::vector<CornerTriangle>{{0, 1, 3}, {1, 2, 3}}));
  EXPECT_EQ(triangulate(reflex_2), (std::vector<CornerTriangle>{{0, 1, 2}, {0, 2, 3}}));
  for (const Polygon& p : {reflex_1, reflex_2}) expect_exact_triangulation(p, "dart");
}

TEST(PolygonTriangulation, RandomGarbageNeitherCrashesNorHangs) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (std::size_t n : {5u, 6u, 13u, 100u, 1000u, 20000u}) {
    Polygon p;
    for (std::size_t i = 0; i < n; ++i) {
      if (i > 0 && rng() % 7 == 0)
        p.push_back(p[rng() % i]);  // repeated corners
      else
        p.emplace_back(u(rng), u(rng), rng() % 3 == 0 ? u(rng) : 0.0f);
    }
    std::size_t work = 0;
    const std::vector<CornerTriangle> tris = triangulate(p, nullptr, &work);
    ASSERT_EQ(tris.size(), n - 2);
    for (const CornerTriangle& t : tris)
      for (const std::uint32_t i : t) ASSERT_LT(i, n);
    EXPECT_LE(work, PolygonTriangulator::budget(n) + 4 * n) << n;
  }
  const float nan = std::nanf(""), inf = INFINITY;
  for (const Polygon& p :
       {Polygon{vec4(0, 0, 0), vec4(1, 0, 0), vec4(nan, 1, 0), vec4(0, 1, 0), vec4(0, 2, 0)},
        Polygon{vec4(0, 0, 0), vec4(inf, 0, 0), vec4(1, 1, 0), vec4(0, 1, 0), vec4(0, 2, 0)},
        Polygon(7, vec4(1, 2, 3)),  // one point
        Polygon{vec4(0, 0, 0), vec4(1, 0, 0), vec4(2, 0, 0), vec4(3, 0, 0), vec4(4, 0, 0)},
        Polygon{vec4(0, 0, 0), vec4(1, -1, 0), vec4(1, 1, 0), vec4(0, 0, 0), vec4(-1, -1, 0),
                vec4(-1, 1, 0)}}) {  // a figure eight: no net area
    bool complete = true;
    const std::vector<CornerTriangle> tris = triangulate(p, &complete);
    EXPECT_EQ(tris.size(), p.size() - 2);
    EXPECT_FALSE(complete);
  }
}

TEST(PolygonTriangulation, FewerThanFourCornersNeedNoWork) {
  EXPECT_TRUE(triangulate({}).empty());
  EXPECT_TRUE(triangulate({vec4(0, 0, 0), vec4(1, 0, 0)}).empty());
  EXPECT_EQ(triangulate({vec4(0, 0, 0), vec4(1, 0, 0), vec4(0, 1, 0)}),
            (std::vector<CornerTriangle>{{0, 1, 2}}));
}

// 100,000 and 200,000 corners (a tenth in the sanitizer build): a circle (in floats, more
// than half its corners come out reflex), stars (half reflex), a thin ring with a bridge, a
// spiral and a comb, all complete, in work that grows as n log n (budget(n) is 32 n log2 n).
TEST(PolygonTriangulation, WorkIsNearLinearInTheCornerCount) {
  for (const std::size_t size : {100000u, 200000u}) {
    const std::size_t n = size / test::kSampleScale;
    const Polygon shapes[] = {regular(n),          star(n),
                              star(n, 0.3),        bridged(regular(n / 2), regular(n / 2, 0.99)),
                              spiral(n / 2, 20.0), comb(int(n / 4))};
    const char* names[] = {"circle", "star", "spiky star", "ring", "spiral", "comb"};
    for (int s = 0; s < 6; ++s) {
      bool complete = false;
      std::size_t work = 0;
      const std::vector<CornerTriangle> tris = triangulate(shapes[s], &complete, &work);
      EXPECT_TRUE(complete) << names[s];
      EXPECT_EQ(tris.size(), shapes[s].size() - 2) << names[s];
      const double corners = double(shapes[s].size());
      const double per_n_log_n = double(work) / (corners * std::log2(corners));
      std::printf("[ measure  ] %s of %zu corners: %.2f n log2 n work units\n", names[s],
                  shapes[s].size(), per_n_log_n);
      EXPECT_LT(per_n_log_n, 12.0) << names[s];
    }
  }
}

}  // namespace
}  // namespace rt2::io
