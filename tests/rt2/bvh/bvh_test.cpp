// The BVH: structure invariants of the binary builder and of the wide tree collapsed from
// it, and closest / any hit through the wide traversal, for every instruction set and both
// triangle tests, against brute force over every primitive.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <tuple>

#include "mlib/fpmode.h"
#include "rt2/bvh/accel.h"
#include "rt2/scene/builtin_scene.h"
#include "rt2/base/error.h"
#include "rt2/render/trace.h"
#include "tests/rt2/test_util.h"

namespace rt2 {
namespace {

using test::kSampleScale;

// Checks, for every runnable ISA, both node layouts and both triangle tests, that the wide
// BVH's closest hit is brute force's: the same t, u, v and primitive, bit for bit (each
// primitive's values do not depend on the visiting order, and ties go to the smaller index in
// both). Returns the number of rays that hit.
std::size_t expect_closest_equals_brute_force(const Scene& scene, const BvhConfig& config,
                                              const std::vector<Ray>& rays) {
  std::size_t hits = 0;
  for (Isa isa : test::runnable_isas())
    for (NodeLayout layout : {NodeLayout::plain, NodeLayout::quantized}) {
      BvhConfig layout_config = config;
      layout_config.nodes = layout;
      const Accel acc = Accel::build(scene, layout_config, isa);
      for (bool watertight : {false, true}) {
        std::vector<Hit> bvh(rays.size());
        const std::vector<float> t_max(rays.size(), kInfinity);
        trace_closest(acc, {watertight}, rays.data(), t_max.data(), rays.size(), bvh.data());
        std::size_t mismatches = 0;
        hits = 0;
  #pragma omp parallel for reduction(+ : hits, mismatches) schedule(dynamic, 256)
        for (std::size_t i = 0; i < rays.size(); ++i) {
          const Hit ref = test::brute_force(acc, rays[i], 0.0f, kInfinity, watertight);
          hits += ref.found();
          const Hit& b = bvh[i];
          mismatches += !(b.t == ref.t && b.prim == ref.prim &&
                          (prim_tag(b.prim) != kTriangleTag || (b.u == ref.u && b.v == ref.v)));
        }
        EXPECT_EQ(mismatches, 0u) << isa_name(isa) << (watertight ? " watertight" : " fast")
                                  << (layout == NodeLayout::quantized ? " quantized" : " plain");
      }
    }
  return hits;
}

// Any hit against closest hit on the segments (0, t_max[i]) of `rays`: the rays where
// trace_occluded and trace_closest disagree about a hit, and the rays blocked.
struct AnyVsClosest {
  std::size_t disagree = 0, blocked = 0;
};
AnyVsClosest any_vs_closest(const Accel& acc, bool watertight, const std::vector<Ray>& rays,
                            const std::vector<float>& t_max) {
  std::vector<std::uint8_t> occluded(rays.size());
  std::vector<Hit> hits(rays.size());
  trace_occluded(acc, {watertight}, rays.data(), t_max.data(), rays.size(), occluded.data());
  trace_closest(acc, {watertight}, rays.data(), t_max.data(), rays.size(), hits.data());
  AnyVsClosest a;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    a.disagree += (occluded[i] != 0) != hits[i].found();
    a.blocked += occluded[i];
  }
  return a;
}

class BvhVsBruteForce : public ::testing::TestWithParam<std::tuple<std::uint32_t, Split>> {};

TEST_P(BvhVsBruteForce, ClosestHitEqualsBruteForceOnRandomSoup) {
  const auto [leaf, split] = GetParam();
  const Scene scene = test::geometry_scene({test::random_soup(300, 0.4f, 7 + leaf)},
                                           {Sphere{vec4(0.3f, 0.2f, 0.1f), 0.2f}});
  const BvhConfig config{leaf, split, 16};
  const auto rays = test::random_rays(Accel::build(scene, config), 50000 / kSampleScale, 11 + leaf);
  const std::size_t hits = expect_closest_equals_brute_force(scene, config, rays);
  EXPECT_GT(hits, rays.size() / 3);  // the rays do exercise hits
}

std::string leaf_and_split_name(
    const ::testing::TestParamInfo<std::tuple<std::uint32_t, Split>>& p) {
  return "leaf" + std::to_string(std::get<0>(p.param)) +
         (std::get<1>(p.param) == Split::sah ? "_sah" : "_midpoint");
}

INSTANTIATE_TEST_SUITE_P(LeafSizesAndSplits, BvhVsBruteForce,
                         ::testing::Combine(::testing::Values(1u, 4u, 64u, 4096u),
                                            ::testing::Values(Split::midpoint, Split::sah)),
                         leaf_and_split_name);

// n random triangles in the plane z = 1 about centres uniform in the unit square, each
// vertex within size / 2 of its centre in x and y (degenerate ones dropped).
Mesh triangles_at_z1(std::uint32_t n, float size, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  Mesh m;
  for (std::uint32_t i = 0; i < n; ++i) {
    const float cx = u(rng), cy = u(rng);
    for (int k = 0; k < 3; ++k)
      m.positions.push_back(
          vec4(cx + size * (u(rng) - 0.5f), cy + size * (u(rng) - 0.5f), 1.0f));
    m.faces.push_back({3 * i, 3 * i + 1, 3 * i + 2});
  }
  m.face_materials.assign(m.faces.size(), 0);
  m.drop_degenerate();
  return m;
}

TEST(Bvh, TiesAtEqualTGoToTheSmallerIndexWhateverTheLeavesAndSlotsOrder) {
  // Overlapping triangles in the plane z = 1, shot exactly along +z: the fast test computes
  // t = N.z / N.z = 1 for every one of them, so nearly every ray hits several at the same t
  // and the smaller index must win, whichever leaf, block, lane or node slot holds it (the
  // 8-wide walks test two leaves at once, where the two blocks' indices are not ordered).
  std::mt19937 rng(23);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const Scene scene = test::geometry_scene({triangles_at_z1(400, 0.4f, rng)});
  std::vector<Ray> rays;
  for (int i = 0; i < 20000 / kSampleScale; ++i)
    rays.push_back(Ray(vec4(0.1f + 0.8f * u(rng), 0.1f + 0.8f * u(rng), 0.0f), vec4(0, 0, 1)));
  for (std::uint32_t leaf : {1u, 2u, 4u}) {
    const BvhConfig config{leaf, Split::sah, 16};
    EXPECT_GT(expect_closest_equals_brute_force(scene, config, rays), rays.size() * 9 / 10) << leaf;
  }
}

TEST(Bvh, TrianglesWinTiesWithAPlaneAtTheSameTAndThePlaneKeepsTheRaysTheyMiss) {
  // Triangles in the plane z = 1 and the plane z = 1 itself, shot along +z: where a ray
  // meets a triangle both are at t = 1 (to the rounding of each test), and the triangle
  // must win a tie, as brute force decides; elsewhere the plane's hit must come back whole.
  // The walk starts from the plane's hit (its t and primitive) and returns it when no
  // triangle is nearer.
  std::mt19937 rng(29);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  Scene scene = test::geometry_scene({triangles_at_z1(200, 0.2f, rng)});
  scene.planes.push_back(Plane{vec4(0, 0, 1), -1.0f});
  scene.plane_materials.push_back(0);
  std::vector<Ray> rays;
  for (int i = 0; i < 20000 / kSampleScale; ++i)
    rays.push_back(Ray(vec4(1.4f * u(rng) - 0.2f, 1.4f * u(rng) - 0.2f, 0.0f), vec4(0, 0, 1)));
  EXPECT_EQ(expect_closest_equals_brute_force(scene, BvhConfig{4, Split::sah, 16}, rays),
            rays.size());  // every ray meets the plane
  const Accel acc = Accel::build(scene, BvhConfig{4, Split::sah, 16});
  std::size_t on_plane = 0, on_triangle = 0;
  for (const Ray& r : rays) {
    const Hit h = trace_closest(acc, r, kInfinity, TraceOptions{false});
    on_plane += h.prim == (kPlaneTag | 0u);
    on_triangle += prim_tag(h.prim) == kTriangleTag;
  }
  EXPECT_GT(on_plane, rays.size() / 10);  // both outcomes are exercised
  EXPECT_GT(on_triangle, rays.size() / 10);
}

TEST(Bvh, AnyHitOfTwoLeavesTestedTogetherFindsTheOnlyTriangleInTheSegmentInAnyBlock) {
  // Two leaves of three blocks each, far apart along x (max leaf size 16), each holding
  // twelve small triangles in the cells of a 4 x 3 grid over the square 0 <= y, z < 1, one
  // to a cell at shuffled depths, the near leaf's in the cells' lower halves and the far
  // one's in the upper: a ray along x meets at most one triangle, in any block of either. The any-hit walks of the 8- and 16-wide trees test the two leaves' first
  // blocks together and must still look at the rest of each leaf: occlusion must agree
  // with the closest hit on segments long enough to reach both leaves.
  for (unsigned seed = 1; seed <= 8; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    Mesh m;
    for (float x0 : {0.0f, 10.0f}) {
      std::vector<int> cells(12);
      std::iota(cells.begin(), cells.end(), 0);
      std::shuffle(cells.begin(), cells.end(), rng);
      for (int k = 0; k < 12; ++k) {
        const float y = float(cells[k] % 4) / 4.0f, z = float(cells[k] / 4) / 3.0f;
        const float x = x0 + 0.01f * float(k);
        const auto first = static_cast<std::uint32_t>(m.positions.size());
        const float h = 1.0f / 3.0f;
        if (x0 == 0.0f)  // the near leaf covers the cells' lower halves, the far one the upper
          m.positions.insert(m.positions.end(),
                             {vec4(x, y, z), vec4(x, y + 0.25f, z), vec4(x, y, z + h)});
        else
          m.positions.insert(m.positions.end(), {vec4(x, y + 0.25f, z + h), vec4(x, y, z + h),
                                                 vec4(x, y + 0.25f, z)});
        m.faces.push_back({first, first + 1, first + 2});
      }
    }
    m.face_materials.assign(m.faces.size(), 0);
    const Scene scene = test::geometry_scene({m});
    std::vector<Ray> rays;
    std::vector<float> t_max;
    for (int i = 0; i < 400; ++i) {
      rays.push_back(Ray(vec4(-1.0f, u(rng), u(rng)), vec4(1, 0, 0)));
      rays.push_back(Ray(vec4(11.0f, u(rng), u(rng)), vec4(-1, 0, 0)));
      t_max.push_back(11.5f), t_max.push_back(11.5f);  // through both leaves
    }
    for (Isa isa : test::runnable_isas()) {
      const Accel acc = Accel::build(scene, BvhConfig{16, Split::sah, 16}, isa);
      for (bool watertight : {false, true}) {
        const AnyVsClosest a = any_vs_closest(acc, watertight, rays, t_max);
        EXPECT_EQ(a.disagree, 0u) << seed << ' ' << isa_name(isa);
        EXPECT_GT(a.blocked, rays.size() * 9 / 10);  // the halves cover the square
      }
    }
  }
}

TEST(Bvh, TwoLeavesOfSeveralBlocksTestedTogetherFindHitsInEveryBlock) {
  // Two stacks of twelve parallel triangles, far apart along x, each one leaf of three
  // blocks (max leaf size 16): a ray along the x axis enters both leaves and no other child,
  // so the 8- and 16-wide walks test the two leaves' first blocks together and the rest of
  // each leaf after. The stacks' triangles come in a shuffled order, so that the nearest one
  // lies in a later block for some seeds and rays.
  for (unsigned seed = 1; seed <= 8; ++seed) {
    Mesh m;
    std::vector<float> xs;
    for (int i = 0; i < 12; ++i) xs.push_back(0.01f * float(i)), xs.push_back(10.0f + 0.01f * float(i));
    std::shuffle(xs.begin(), xs.end(), std::mt19937(seed));
    for (float x : xs) {
      const auto first = static_cast<std::uint32_t>(m.positions.size());
      m.positions.insert(m.positions.end(), {vec4(x, -1, -1), vec4(x, 3, -1), vec4(x, -1, 3)});
      m.faces.push_back({first, first + 1, first + 2});
    }
    m.face_materials.assign(m.faces.size(), 0);
    const Scene scene = test::geometry_scene({m});
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<Ray> rays;
    for (int i = 0; i < 200; ++i) {
      rays.push_back(Ray(vec4(-1.0f, u(rng), u(rng)), vec4(1, 0, 0)));
      rays.push_back(Ray(vec4(11.0f, u(rng), u(rng)), vec4(-1, 0, 0)));
    }
    EXPECT_EQ(expect_closest_equals_brute_force(scene, BvhConfig{16, Split::sah, 16}, rays),
              rays.size())
        << seed;
  }
}

TEST(Bvh, ClosestHitEqualsBruteForceOnTheChairMesh) {
  Scene scene = make_default_scene();
  scene.planes.clear();
  scene.plane_materials.clear();
  for (Split split : {Split::sah, Split::midpoint}) {
    const BvhConfig config{4, split, 16};
    const auto rays = test::random_rays(Accel::build(scene, config), 20000 / kSampleScale, 5, 1.5f);
    EXPECT_GT(expect_closest_equals_brute_force(scene, config, rays), rays.size() / 3);
  }
}

// The closest-hit query lets a ray whose origin lies outside the tree's box go without a walk when
// it misses that box by the slab test (WideBvh::bounds, may_enter). The box is as tight as it gets
// here: a closed box of twelve triangles (faces at non-round coordinates) around a soup, so that
// the tree's box is the mesh's own to the builder's padding. Rays from outside clip it: aimed at
// points of its edges and corners, from near and from a million units out, and rays lying in the
// planes of its faces (a zero direction component: the slab test's infinities and 0 * inf) aimed
// along a face at an edge of the next one. Closest hits must be brute force's, bit for bit, and any
// hit must agree with them on segments ending short of, at and past the aimed-at point.
TEST(Bvh, RaysFromOutsideTheTreesBoxThatClipItOrLieInItsFacesFindBruteForcesHits) {
  // The box straddles the coordinate origin: outward from a face is away from 0.
  const float lo[3] = {-1.3f, -1.25f, -1.2f}, hi[3] = {1.2f, 1.35f, 1.3f};
  const auto corner = [&](int c) {  // bit a of c: the high side of axis a
    return vec4(c & 1 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1], c & 4 ? hi[2] : lo[2]);
  };
  Mesh box;
  box.name = "box";
  for (int c = 0; c < 8; ++c) box.positions.push_back(corner(c));
  // Two triangles per face, the corners of each face in order around it.
  const std::uint32_t faces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1},
                                     {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
  for (const auto& f : faces) {
    box.faces.push_back({f[0], f[1], f[2]});
    box.faces.push_back({f[0], f[2], f[3]});
  }
  box.face_materials.assign(box.faces.size(), 0);
  Mesh mesh = test::random_soup(400, 0.3f, 17);
  mesh.append(box);
  const Scene scene = test::geometry_scene({mesh});

  std::mt19937 rng(19);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  // A point of an edge of the box: corners c and c with bit `axis` set.
  const auto edge_point = [&](int axis) {
    const int c = int(rng() % 8) & ~(1 << axis);
    const vec4 a = corner(c), b = corner(c | 1 << axis);
    return u(rng) < 0.1f ? (u(rng) < 0.5f ? a : b) : a + (b - a) * u(rng);
  };
  std::vector<Ray> rays;
  std::vector<float> reach;  // distance to the aimed-at point
  const auto aim = [&](const vec4& org, const vec4& target) {
    const vec4 d = target - org;
    const float len = std::sqrt(float(dot(d, d)));
    rays.push_back(Ray(org, d / len));
    reach.push_back(len);
  };
  for (int i = 0; i < 6000 / kSampleScale; ++i) {
    const float far = i % 3 == 0 ? 1e6f : 4.0f;  // a million units out, or near
    aim(far * test::random_direction(rng), edge_point(int(rng() % 3)));
  }
  for (int i = 0; i < 3000 / kSampleScale; ++i) {
    // In the plane of a face (axis a at its low or high side), from outside the face,
    // towards a point of an edge that face shares with a face across axis b.
    const int a = int(rng() % 3), b = (a + 1 + int(rng() % 2)) % 3, c = 3 - a - b;
    const float plane = rng() % 2 ? hi[a] : lo[a];
    vec4 target, org;
    target[a] = org[a] = plane;
    target[b] = rng() % 2 ? hi[b] : lo[b];
    target[c] = lo[c] + (hi[c] - lo[c]) * u(rng);
    org[b] = target[b] + (target[b] > 0 ? 1.0f : -1.0f) * (0.5f + 3.0f * u(rng));
    org[c] = target[c] + 4.0f * (u(rng) - 0.5f);
    aim(org, target);
  }
  const auto inside = [&](const vec4& p) {
    return p[0] >= lo[0] && p[0] <= hi[0] && p[1] >= lo[1] && p[1] <= hi[1] && p[2] >= lo[2] &&
           p[2] <= hi[2];
  };
  for (const Ray& r : rays) ASSERT_FALSE(inside(r.org));  // every ray starts outside the box
  const BvhConfig config{4, Split::sah, 16};
  const std::size_t hits = expect_closest_equals_brute_force(scene, config, rays);
  EXPECT_GT(hits, rays.size() / 2);   // the clipping rays hit the box's faces ...
  EXPECT_LT(hits, rays.size());       // ... and some rays miss it
  for (Isa isa : test::runnable_isas()) {
    const Accel acc = Accel::build(scene, config, isa);
    for (float part : {0.5f, 1.0f, 1.5f}) {
      std::vector<float> t_max(rays.size());
      for (std::size_t i = 0; i < rays.size(); ++i) t_max[i] = reach[i] * part;
      for (bool watertight : {false, true}) {
        const AnyVsClosest a = any_vs_closest(acc, watertight, rays, t_max);
        EXPECT_EQ(a.disagree, 0u)
            << isa_name(isa) << " " << part << (watertight ? " watertight" : " fast");
        if (part > 1.0f) {
          EXPECT_GT(a.blocked, rays.size() / 2);
        }
      }
    }
  }
}

TEST(Bvh, AnyHitAgreesWithClosestHitOnSegments) {
  const Scene scene = test::geometry_scene({test::random_soup(500, 0.3f, 3)},
                                           {Sphere{vec4(0, 0, 0), 0.3f}});
  for (Isa isa : test::runnable_isas()) {
    const Accel acc = Accel::build(scene, BvhConfig{4, Split::sah, 16}, isa);
    const auto rays = test::random_rays(acc, 50000 / kSampleScale, 4);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> len(0.0f, 4.0f);
    std::vector<float> t_max(rays.size());
    for (float& t : t_max) t = len(rng);
    for (bool watertight : {false, true}) {
      const AnyVsClosest a = any_vs_closest(acc, watertight, rays, t_max);
      EXPECT_EQ(a.disagree, 0u) << isa_name(isa);
      EXPECT_GT(a.blocked, rays.size() / 10);
    }
  }
}

// The node test of the AVX2 and AVX-512 kernels takes each slab distance as one FMA,
// b * (1 / dir) + c, with c = -org * (1 / dir) rounded once per ray
// (rt2/kernel/wide_traverse.h). Its rounding is largest beside the distances where the scene
// lies far from the coordinate origin and rays start on it, as secondary rays do: a triangle
// soup three million units out, rays leaving points of its triangles in random directions or
// aimed at other triangles' vertices and edges (where boxes' faces lie). Closest hits must be
// brute force's, bit for bit, and any-hit must agree with them on segments.
TEST(Bvh, RaysLeavingTrianglesThreeMillionUnitsOutFindBruteForcesHitsWithEveryNodeTest) {
  Mesh soup = test::random_soup(400, 0.4f, 21);
  const vec4 far(1.5e6f, -2e6f, 3e6f);
  for (vec4& p : soup.positions) p = far + 100.0f * p;
  soup.drop_degenerate();
  const Scene scene = test::geometry_scene({soup});
  const Accel probe = Accel::build(scene, BvhConfig{});
  std::mt19937 rng(22);
  std::uniform_real_distribution<float> u(0.0f, 1.0f), len(0.0f, 300.0f);
  const auto point_of = [&](const Triangle& t, int edge) {
    float a = u(rng), b = u(rng);
    if (a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
    if (edge == 1) a = 0.0f;             // on the edge V0 V2
    if (edge == 2) b = 1.0f - a;         // on the edge V1 V2
    if (edge == 3) a = 0.0f, b = 0.0f;   // the vertex V0
    return t.point(a, b);
  };
  std::vector<Ray> rays;
  std::vector<float> t_max;
  for (int i = 0; i < 40000 / kSampleScale; ++i) {
    const Triangle& from = probe.tris[rng() % probe.tris.size()];
    const vec4 org = point_of(from, 0);
    if (i % 2 == 0) {
      rays.emplace_back(org, test::random_direction(rng));
    } else {
      const vec4 d = point_of(probe.tris[rng() % probe.tris.size()], 1 + i / 2 % 3) - org;
      if (!(float(dot(d, d)) > 1e-6f)) continue;
      rays.emplace_back(org, normalize(d));
    }
    t_max.push_back(len(rng));
  }
  const std::size_t hits = expect_closest_equals_brute_force(scene, BvhConfig{}, rays);
  EXPECT_GT(hits, rays.size() / 4);
  for (Isa isa : test::runnable_isas()) {
    const Accel acc = Accel::build(scene, BvhConfig{}, isa);
    for (bool watertight : {false, true}) {
      EXPECT_EQ(any_vs_closest(acc, watertight, rays, t_max).disagree, 0u)
          << isa_name(isa) << (watertight ? " watertight" : " fast");
    }
  }
}

TEST(Bvh, EveryIsaFindsTheSameHitsBitForBit) {
  Scene scene = make_default_scene();
  const auto rays = test::random_rays(Accel::build(scene, BvhConfig{}), 20000 / kSampleScale, 8, 2.0f);
  for (bool watertight : {false, true}) {
    std::vector<Hit> first;
    for (Isa isa : test::runnable_isas()) {
      const Accel acc = Accel::build(scene, BvhConfig{}, isa);
      std::vector<Hit> hits(rays.size());
      const std::vector<float> t_max(rays.size(), kInfinity);
      trace_closest(acc, {watertight}, rays.data(), t_max.data(), rays.size(), hits.data());
      if (first.empty()) {
        first = hits;
        continue;
      }
      std::size_t differ = 0;
      for (std::size_t i = 0; i < rays.size(); ++i)
        differ += std::memcmp(&hits[i], &first[i], sizeof(Hit)) != 0;
      EXPECT_EQ(differ, 0u) << isa_name(isa);
    }
  }
}

// The wide tree holds every triangle exactly once, in blocks of at most four whose leaf
// runs end with a block marked last; every triangle lies in the box of each slot above it;
// a plain node's child boxes are inside its own (a quantized one's are rounded outward in
// its own frame); no node has more than its width of children, nor fewer than two.
template <int N>
void expect_wide_tree_is_well_formed(const Accel& acc, std::uint32_t max_leaf) {
  const WideBvh<N>& w = acc.wide<N>();
  std::vector<int> seen(acc.tris.size(), 0);
  std::uint32_t leaves = 0;
  std::vector<Aabb> above;  // the slot boxes from the root down to the current leaf
  const auto visit_leaf = [&](std::uint32_t first) {
    ++leaves;
    std::uint32_t count = 0;
    for (std::uint32_t b = first;; ++b) {
      const TriangleBlock& block = acc.blocks[b];
      for (int l = 0; l < 4; ++l)
        if (block.prim_of(l) != TriangleBlock::kNoPrim) {
          ++seen[block.prim_of(l)];
          ++count;
          const Triangle& t = acc.tris[block.prim_of(l)];
          for (const Aabb& box : above)
            for (int v = 0; v < 3; ++v) EXPECT_TRUE(box.contains(t.vertex(v)));
        }
      if (block.last()) break;
    }
    EXPECT_LE(count, max_leaf);
  };
  w.with_nodes([&](const auto* nodes) {
    const auto visit = [&](const auto& self, std::uint32_t ref) -> void {
      if (ref & kLeaf) {
        visit_leaf(ref & ~kLeaf);
        return;
      }
      const auto& node = nodes[ref];
      EXPECT_GE(node.slots(), 2);
      EXPECT_LE(node.slots(), N);
      for (int i = 0; i < node.slots(); ++i) {
        if (!w.quantized && !(node.child[i] & kLeaf))
          for (int k = 0; k < nodes[node.child[i]].slots(); ++k)
            for (int a = 0; a < 3; ++a) {
              EXPECT_GE(nodes[node.child[i]].box(k).lo[a], node.box(i).lo[a]);
              EXPECT_LE(nodes[node.child[i]].box(k).hi[a], node.box(i).hi[a]);
            }
        above.push_back(node.box(i));
        self(self, node.child[i]);
        above.pop_back();
      }
    };
    visit(visit, w.root);
  });
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int c) { return c == 1; }));
  EXPECT_EQ(leaves, acc.stats.leaves);
  EXPECT_EQ(leaves, w.leaves);
  // The tree's box (WideBvh::bounds), which a ray from outside must enter to be walked,
  // holds every triangle.
  for (const Triangle& t : acc.tris)
    for (int i = 0; i < 3; ++i) EXPECT_TRUE(w.bounds.contains(t.vertex(i)));
}

TEST(Bvh, TheWideTreeHoldsEveryTriangleOnceInBlocksUnderItsParentsBox) {
  const Scene scene = test::geometry_scene({test::random_soup(3000, 0.2f, 13)});
  for (std::uint32_t leaf : {1u, 4u, 7u, 64u, 5000u})
    for (Isa isa : test::runnable_isas())
      for (NodeLayout layout : {NodeLayout::plain, NodeLayout::quantized}) {
        BvhConfig config{leaf, Split::sah, 16};
        config.nodes = layout;
        const Accel acc = Accel::build(scene, config, isa);
        ASSERT_EQ(acc.quantized_nodes(), layout == NodeLayout::quantized);
        with_bvh_width(isa, [&](auto n) { expect_wide_tree_is_well_formed<n()>(acc, leaf); });
      }
}

// Every node's octant orders (WideNode::octant_order) list each slot once per octant:
// first the children, farthest first along the octant's diagonal (by their boxes'
// centres), then the unused slots; octant 7 - o is octant o reversed; a node of two
// children or fewer keeps the identity (the walk orders two children by distance).
template <int N>
void expect_octant_orders(const Accel& acc) {
  const WideBvh<N>& w = acc.wide<N>();
  constexpr unsigned kSlotMask = (1u << kOrderBits<N>) - 1;
  for (const WideNode<N>& node : w.nodes) {
    int n = 0;
    while (n < N && !(node.bounds[0][n] > node.bounds[1][n])) ++n;
    for (int o = 0; o < 8; ++o) {
      int slot[N];
      unsigned seen = 0;
      for (int j = 0; j < N; ++j) {
        slot[j] = int(node.octant_order[j] >> (kOrderBits<N> * o) & kSlotMask);
        ASSERT_LT(slot[j], N);
        seen |= 1u << slot[j];
      }
      ASSERT_EQ(seen, (1u << N) - 1) << "octant " << o << ": not a permutation";
      if (n <= 2) {
        for (int j = 0; j < N; ++j) EXPECT_EQ(slot[j], j);
        continue;
      }
      const auto key = [&](int i) {
        double k = 0.0;
        for (int a = 0; a < 3; ++a) {
          const double c = double(node.bounds[2 * a][i]) + node.bounds[2 * a + 1][i];
          k += (o >> a & 1) ? -c : c;
        }
        return k;
      };
      for (int j = 0; j < N; ++j) EXPECT_EQ(j < n, slot[j] < n) << "children come first";
      for (int j = 1; j < n; ++j)
        EXPECT_GE(key(slot[j - 1]), key(slot[j]) - 1e-6 * (1.0 + std::fabs(key(slot[j]))))
            << "octant " << o << ", position " << j;
      for (int j = 0; j < n; ++j)
        EXPECT_EQ(int(node.octant_order[j] >> (kOrderBits<N> * (7 - o)) & kSlotMask),
                  slot[n - 1 - j])
            << "octant " << 7 - o << " is octant " << o << " reversed";
    }
  }
}

TEST(Bvh, OctantOrdersListEverySlotOnceChildrenFarthestFirstAlongTheDiagonal) {
  const Scene scene = test::geometry_scene({test::random_soup(3000, 0.2f, 15)});
  for (std::uint32_t leaf : {1u, 4u, 16u})
    for (Isa isa : test::runnable_isas()) {
      const Accel acc = Accel::build(scene, BvhConfig{leaf, Split::sah, 16}, isa);
      with_bvh_width(isa, [&](auto n) { expect_octant_orders<n()>(acc); });
    }
}

TEST(Bvh, CollapsingMakesFewerNodesThanTheBinaryTree) {
  const Scene scene = test::geometry_scene({test::random_soup(10000, 0.1f, 14)});
  for (Isa isa : test::runnable_isas()) {
    const Accel acc = Accel::build(scene, BvhConfig{}, isa);
    const double ratio = double(acc.stats.nodes - acc.stats.leaves) / acc.wide_nodes;
    // A full binary tree of L leaves has L - 1 inner nodes; a full N-wide one (L - 1)/(N - 1),
    // a collapsed one somewhat more (a cut cannot always fill N slots).
    EXPECT_GT(ratio, bvh_width(isa) / 2.0) << isa_name(isa);
    EXPECT_LE(acc.blocks.size(), (acc.tris.size() + 3) / 4 + acc.stats.leaves);
  }
}

// The collapse's cost, the sum of the areas of the wide nodes' boxes (the root's left out:
// it is always one), read back from the wide tree: every slot that holds an inner node
// holds that binary node's box.
double area_of_box(const float* lo, const float* hi) {
  const float x = hi[0] - lo[0], y = hi[1] - lo[1], z = hi[2] - lo[2];
  return double(x * y + y * z + z * x);
}

template <int N>
double wide_node_areas(const WideBvh<N>& w) {
  double sum = 0.0;
  for (const WideNode<N>& node : w.nodes)
    for (int i = 0; i < N; ++i) {
      if (node.bounds[0][i] > node.bounds[1][i] || (node.child[i] & kLeaf)) continue;
      const float lo[3] = {node.bounds[0][i], node.bounds[2][i], node.bounds[4][i]};
      const float hi[3] = {node.bounds[1][i], node.bounds[3][i], node.bounds[5][i]};
      sum += area_of_box(lo, hi);
    }
  return sum;
}

// The least cost of the wide nodes below binary node n, n a wide node, by trying every way
// to cut its subtree into at most N slots (the frontiers of its children's subtrees).
class ExhaustiveCollapse {
 public:
  ExhaustiveCollapse(const Bvh& bvh, int n) : bvh_(bvh), n_(n), memo_(bvh.nodes.size(), -1.0) {}

  double below(std::uint32_t node) {
    if (memo_[node] >= 0.0) return memo_[node];
    const BvhNode& b = bvh_.nodes[node];
    double best = std::numeric_limits<double>::infinity();
    for (const auto& left : frontiers(node + 1))
      for (const auto& right : frontiers(b.offset)) {
        if (int(left.size() + right.size()) > n_) continue;
        double cost = 0.0;
        for (const auto* side : {&left, &right})
          for (std::uint32_t m : *side)
            if (!bvh_.nodes[m].is_leaf())
              cost += area_of_box(bvh_.nodes[m].lo, bvh_.nodes[m].hi) + below(m);
        best = std::min(best, cost);
      }
    return memo_[node] = best;
  }

 private:
  // Every set of at most N nodes that cuts subtree m: m itself, or a cut of each child's.
  std::vector<std::vector<std::uint32_t>> frontiers(std::uint32_t m) const {
    std::vector<std::vector<std::uint32_t>> out{{m}};
    const BvhNode& b = bvh_.nodes[m];
    if (b.is_leaf()) return out;
    for (const auto& l : frontiers(m + 1))
      for (const auto& r : frontiers(b.offset)) {
        if (int(l.size() + r.size()) > n_) continue;
        out.push_back(l);
        out.back().insert(out.back().end(), r.begin(), r.end());
      }
    return out;
  }

  const Bvh& bvh_;
  int n_;
  std::vector<double> memo_;
};

// The wide tree over a mesh's triangles as Accel::build makes it: the binary SAH tree with
// leaves of at most max_leaf triangles, collapsed into nodes of N children.
template <int N>
struct CollapsedMesh {
  Bvh bvh;
  TriangleBlocks blocks;
  WideBvh<N> wide;

  CollapsedMesh(const Mesh& mesh, std::uint32_t max_leaf) {
    std::vector<Triangle> tris;
    std::vector<Aabb> boxes;
    for (const auto& f : mesh.faces) {
      tris.push_back(Triangle::make(mesh.positions[f[0]], mesh.positions[f[1]], mesh.positions[f[2]]));
      Aabb b;
      for (std::uint32_t v : f) b.grow(mesh.positions[v]);
      boxes.push_back(b);
    }
    bvh = build_bvh(boxes, BvhConfig{max_leaf, Split::sah, 16});
    wide = collapse_bvh<N>(bvh, tris, blocks);
  }
};

template <int N>
void expect_collapse_is_least_cost(unsigned seed, std::size_t triangles) {
  const CollapsedMesh<N> c(test::random_soup(triangles, 0.5f, seed), 1);
  const Bvh& bvh = c.bvh;
  const WideBvh<N>& w = c.wide;
  ExhaustiveCollapse oracle(bvh, N);
  const double least = oracle.below(0);
  // The plan sums areas in float: within a few ulps (per area summed) of the least.
  EXPECT_NEAR(wide_node_areas(w), least, 1e-5 * least) << "N = " << N << ", seed " << seed;
}

TEST(Bvh, CollapseGivesTheLeastSumOfWideNodeAreasThatExhaustiveSearchFinds) {
  for (unsigned seed = 1; seed <= 12; ++seed) {
    expect_collapse_is_least_cost<4>(seed, 14 + seed);
    expect_collapse_is_least_cost<8>(seed, 14 + seed);
    expect_collapse_is_least_cost<16>(seed, 20 + seed);
  }
}

// Whether the line p + s d, s over all reals, meets the box [lo, hi] (in double precision).
bool line_meets_box(const double* p, const double* d, const float* lo, const float* hi) {
  double enter = -std::numeric_limits<double>::infinity();
  double leave = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0.0) {
      if (p[a] < lo[a] || p[a] > hi[a]) return false;
      continue;
    }
    double t0 = (lo[a] - p[a]) / d[a], t1 = (hi[a] - p[a]) / d[a];
    if (t0 > t1) std::swap(t0, t1);
    enter = std::max(enter, t0);
    leave = std::min(leave, t1);
  }
  return enter <= leave;
}

// wide_sah's figures against what they predict: random lines through the root's box,
// isotropic (direction uniform on the sphere, position uniform across the plane normal to
// it: the measure under which Cauchy's formula holds), each checked against every slot's
// box by brute force, counting the inner nodes (the root included) and the leaf blocks
// (a leaf's blocks when its box is met) it meets.
template <int N>
void expect_sah_is_what_random_lines_meet(std::uint32_t max_leaf, unsigned seed) {
  const CollapsedMesh<N> c(test::random_soup(800, 0.3f, seed), max_leaf);
  const WideBvh<N>& w = c.wide;
  const TriangleBlocks& blocks = c.blocks;
  ASSERT_EQ(w.root, 0u);
  const WideSah sah = wide_sah(w, blocks.data());

  float lo[3], hi[3];  // the root's box: the union of its slots'
  for (int a = 0; a < 3; ++a) {
    lo[a] = *std::min_element(w.nodes[0].bounds[2 * a], w.nodes[0].bounds[2 * a] + N);
    hi[a] = *std::max_element(w.nodes[0].bounds[2 * a + 1], w.nodes[0].bounds[2 * a + 1] + N);
  }
  double centre[3], radius = 0.0;
  for (int a = 0; a < 3; ++a) {
    centre[a] = 0.5 * (double(lo[a]) + hi[a]);
    radius += (double(hi[a]) - lo[a]) * (double(hi[a]) - lo[a]);
  }
  radius = 0.5 * std::sqrt(radius);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> across(-radius, radius);
  const int lines = 20000;
  double nodes = 0.0, leaves = 0.0;
  for (int kept = 0; kept < lines;) {
    const vec4 dir = test::random_direction(rng);
    const double d[3] = {dir[0], dir[1], dir[2]};
    const double h[3] = {std::fabs(d[0]) < 0.9 ? 1.0 : 0.0, std::fabs(d[0]) < 0.9 ? 0.0 : 1.0, 0.0};
    double u[3] = {d[1] * h[2] - d[2] * h[1], d[2] * h[0] - d[0] * h[2], d[0] * h[1] - d[1] * h[0]};
    const double un = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (double& x : u) x /= un;
    const double v[3] = {d[1] * u[2] - d[2] * u[1], d[2] * u[0] - d[0] * u[2], d[0] * u[1] - d[1] * u[0]};
    const double s = across(rng), t = across(rng);
    const double p[3] = {centre[0] + s * u[0] + t * v[0], centre[1] + s * u[1] + t * v[1],
                         centre[2] + s * u[2] + t * v[2]};
    if (!line_meets_box(p, d, lo, hi)) continue;
    ++kept;
    nodes += 1.0;  // the root
    for (const WideNode<N>& node : w.nodes)
      for (int i = 0; i < N; ++i) {
        if (!(node.bounds[0][i] <= node.bounds[1][i])) continue;
        const float blo[3] = {node.bounds[0][i], node.bounds[2][i], node.bounds[4][i]};
        const float bhi[3] = {node.bounds[1][i], node.bounds[3][i], node.bounds[5][i]};
        if (!line_meets_box(p, d, blo, bhi)) continue;
        if (!(node.child[i] & kLeaf)) {
          nodes += 1.0;
          continue;
        }
        for (const TriangleBlock* b = blocks.data() + (node.child[i] & ~kLeaf);; ++b) {
          leaves += 1.0;
          if (b->last()) break;
        }
      }
  }
  // Standard errors are about 0.5 % of each mean here.
  EXPECT_NEAR(sah.nodes, nodes / lines, 0.03 * sah.nodes) << "N = " << N << ", leaf " << max_leaf;
  EXPECT_NEAR(sah.leaves, leaves / lines, 0.03 * sah.leaves) << "N = " << N << ", leaf " << max_leaf;
}

// WideBvh::prefetch_pushed is set exactly for trees (nodes and blocks) of at least
// kPrefetchPushedBytes.
TEST(Bvh, EveryPushedChildIsPrefetchedOnlyInTreesOfKPrefetchPushedBytes) {
  for (std::size_t triangles : {1000u, 300000u}) {
    const CollapsedMesh<8> c(test::random_soup(triangles, 0.01f, 5), 4);
    const std::size_t bytes =
        c.wide.nodes.size() * sizeof(WideNode<8>) + c.blocks.size() * sizeof(TriangleBlock);
    EXPECT_EQ(c.wide.prefetch_pushed, bytes >= kPrefetchPushedBytes) << bytes << " bytes";
    if (triangles > 1000u) {
      EXPECT_TRUE(c.wide.prefetch_pushed) << bytes << " bytes";
    }
  }
}

TEST(Bvh, WideSahIsTheInnerNodesAndLeafBlocksRandomLinesMeet) {
  expect_sah_is_what_random_lines_meet<4>(4, 1);
  expect_sah_is_what_random_lines_meet<8>(4, 2);
  expect_sah_is_what_random_lines_meet<8>(16, 3);  // leaves of several blocks
  expect_sah_is_what_random_lines_meet<16>(4, 5);
  // A tree that is one leaf: no inner node, every line meets its blocks; no tree: nothing.
  const CollapsedMesh<8> leaf(test::random_soup(7, 0.3f, 4), 8);
  ASSERT_TRUE(leaf.wide.root & kLeaf);
  EXPECT_EQ(wide_sah(leaf.wide, leaf.blocks.data()).nodes, 0.0);
  EXPECT_EQ(wide_sah(leaf.wide, leaf.blocks.data()).leaves, 2.0);  // seven triangles: two blocks
  const WideSah none = wide_sah(WideBvh<4>{}, nullptr);
  EXPECT_EQ(none.nodes + none.leaves, 0.0);
}

// `n` boxes with a corner uniform in [-reach, reach]^3 and sides up to `size`.
std::vector<Aabb> random_boxes(int n, unsigned seed, float reach, float size) {
  std::vector<Aabb> boxes;
  std::mt19937 rng(seed);
  for (int i = 0; i < n; ++i) {
    Aabb b;
    const vec4 p = test::random_point(rng, -reach, reach);
    b.grow(p);
    b.grow(p + test::random_point(rng, 0, size));
    boxes.push_back(b);
  }
  return boxes;
}

TEST(Bvh, EveryPrimitiveIsInExactlyOneLeafAndLeavesRespectTheSizeLimit) {
  const std::vector<Aabb> boxes = random_boxes(1000, 1, 10, 1);
  for (std::uint32_t leaf : {1u, 3u, 64u, 5000u}) {
    const Bvh bvh = build_bvh(boxes, BvhConfig{leaf, Split::sah, 16});
    std::vector<int> seen(boxes.size(), 0);
    std::uint32_t leaves = 0;
    for (const BvhNode& n : bvh.nodes) {
      if (!n.is_leaf()) continue;
      ++leaves;
      EXPECT_LE(n.count, leaf);
      for (std::uint32_t i = n.offset; i < n.offset + n.count; ++i) ++seen[bvh.order[i]];
    }
    EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int c) { return c == 1; }));
    EXPECT_EQ(bvh.stats.leaves, leaves);
    EXPECT_EQ(bvh.stats.nodes, 2 * leaves - 1);  // a full binary tree
  }
}

// Large subtrees are built by OpenMP tasks into nodes of their own and appended after: the
// tree is the same node for node at 1 and 2 threads, depth first (the first child follows
// its parent), every primitive in one leaf, every child box inside its parent's.
TEST(Bvh, TreesBuiltByTasksAreTheSameAtAnyThreadCountDepthFirstAndComplete) {
  const std::vector<Aabb> boxes = random_boxes(600000, 4, 100, 2);
  const int threads = omp_get_max_threads();
  for (const Split split : {Split::sah, Split::midpoint}) {
    const BvhConfig config{4, split, 16};
    omp_set_num_threads(1);
    const Bvh one = build_bvh(boxes, config);
    omp_set_num_threads(2);
    const Bvh two = build_bvh(boxes, config);
    omp_set_num_threads(threads);
    ASSERT_EQ(one.nodes.size(), two.nodes.size());
    EXPECT_EQ(std::memcmp(one.nodes.data(), two.nodes.data(), one.nodes.size() * sizeof(BvhNode)), 0);
    EXPECT_TRUE(std::equal(one.order.begin(), one.order.end(), two.order.begin()));
    EXPECT_EQ(one.stats.leaves, two.stats.leaves);
    EXPECT_EQ(one.stats.max_depth, two.stats.max_depth);
    std::vector<int> seen(boxes.size(), 0);
    for (std::uint32_t i = 0; i < two.nodes.size(); ++i) {
      const BvhNode& n = two.nodes[i];
      if (n.is_leaf()) {
        for (std::uint32_t k = n.offset; k < n.offset + n.count; ++k) ++seen[two.order[k]];
        continue;
      }
      ASSERT_GT(n.offset, i + 1);
      ASSERT_LT(n.offset, two.nodes.size());
      for (const std::uint32_t c : {i + 1, n.offset})
        for (int a = 0; a < 3; ++a) {
          EXPECT_GE(two.nodes[c].lo[a], n.lo[a]);
          EXPECT_LE(two.nodes[c].hi[a], n.hi[a]);
        }
    }
    EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int c) { return c == 1; }));
    EXPECT_EQ(two.stats.nodes, 2 * two.stats.leaves - 1);
  }
}

// A large tree is planned and collapsed by OpenMP tasks, each subtree into the nodes and
// blocks the serial collapse gives it, and its triangles are written by a parallel loop:
// the wide tree, its blocks and the triangles are the same bit for bit at 1 and 2 threads,
// at every width, and well formed.
TEST(Bvh, WideTreesCollapsedByTasksAreTheSameBitForBitAtAnyThreadCount) {
  const Scene scene = test::geometry_scene({test::random_soup(400000, 0.05f, 21)});
  const int threads = omp_get_max_threads();
  for (const Isa isa : {Isa::sse41, Isa::avx2, Isa::avx512}) {
    omp_set_num_threads(1);
    const Accel one = Accel::build(scene, BvhConfig{}, isa);
    omp_set_num_threads(2);
    const Accel two = Accel::build(scene, BvhConfig{}, isa);
    omp_set_num_threads(threads);
    ASSERT_GE(one.stats.nodes, 1u << 17) << "a tree the collapse splits into tasks";
    with_bvh_width(isa, [&](auto n) {
      constexpr int N = n();
      const WideBvh<N>& a = one.wide<N>();
      const WideBvh<N>& b = two.wide<N>();
      ASSERT_EQ(a.nodes.size(), b.nodes.size());
      EXPECT_EQ(std::memcmp(a.nodes.data(), b.nodes.data(), a.nodes.size() * sizeof(WideNode<N>)),
                0);
      EXPECT_EQ(a.root, b.root);
      EXPECT_EQ(a.leaves, b.leaves);
      EXPECT_EQ(a.max_depth, b.max_depth);
      expect_wide_tree_is_well_formed<N>(two, BvhConfig{}.max_leaf_size);
    });
    ASSERT_EQ(one.blocks.size(), two.blocks.size());
    EXPECT_EQ(std::memcmp(one.blocks.data(), two.blocks.data(),
                          one.blocks.size() * sizeof(TriangleBlock)),
              0);
    ASSERT_EQ(one.tris.size(), two.tris.size());
    EXPECT_EQ(std::memcmp(one.tris.data(), two.tris.data(), one.tris.size() * sizeof(Triangle)),
              0);
  }
}

// A build's threads compute in the denormal mode of the thread that calls it (FTZ and DAZ,
// mlib/fpmode.h), which rt2 does not set for its workers: over triangles a few hundred
// denormals across, whose normals are denormal unless flushed, the triangles, blocks and
// nodes two threads build for a flushing caller are those one thread builds.
TEST(Bvh, BuildsOnTwoThreadsComputeInTheCallersDenormalMode) {
  Mesh soup = test::random_soup(300000, 0.2f, 23);
  for (vec4& p : soup.positions) p = p * 1e-21f;  // edges ~1e-22: products ~1e-44
  const Scene scene = test::geometry_scene({soup});
  // A new thread starts in its creator's mode: the team's workers are made before the
  // caller flushes, as a program's are before it renders.
  int team = 0;
#pragma omp parallel num_threads(2)
  {
#pragma omp atomic
    ++team;
  }
  ASSERT_EQ(team, 2);
  const unsigned own = mlib::denormal_mode();
  mlib::set_flush_denormals(true);
  const unsigned flush = mlib::denormal_mode();
  mlib::set_denormal_mode(own);
  const mlib::DenormalModeScope flushing(flush);  // the caller's mode until the test ends
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const Accel one = Accel::build(scene, BvhConfig{}, Isa::avx512);
  omp_set_num_threads(2);
  const Accel two = Accel::build(scene, BvhConfig{}, Isa::avx512);
  omp_set_num_threads(threads);
  ASSERT_TRUE(std::any_of(one.tris.begin(), one.tris.end(),
                          [](const Triangle& t) { return t.n[0] == 0.0f && t.v0[0] != 0.0f; }))
      << "some normal flushed to 0";
  ASSERT_EQ(one.tris.size(), two.tris.size());
  EXPECT_EQ(std::memcmp(one.tris.data(), two.tris.data(), one.tris.size() * sizeof(Triangle)), 0);
  ASSERT_EQ(one.blocks.size(), two.blocks.size());
  EXPECT_EQ(std::memcmp(one.blocks.data(), two.blocks.data(),
                        one.blocks.size() * sizeof(TriangleBlock)),
            0);
  ASSERT_EQ(one.bvh16.nodes.size(), two.bvh16.nodes.size());
  EXPECT_EQ(std::memcmp(one.bvh16.nodes.data(), two.bvh16.nodes.data(),
                        one.bvh16.nodes.size() * sizeof(WideNode<16>)),
            0);
}

TEST(Bvh, ChildBoxesAreInsideTheirParent) {
  std::vector<Aabb> boxes;
  for (const Triangle& t : Accel::build(test::geometry_scene({test::random_soup(2000, 0.2f, 9)}),
                                        BvhConfig{}).tris) {
    Aabb b;
    b.grow(t.v0), b.grow(t.v1), b.grow(t.v2);
    boxes.push_back(b);
  }
  const Bvh bvh = build_bvh(boxes, BvhConfig{2, Split::midpoint, 16});
  const auto& nodes = bvh.nodes;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (nodes[i].is_leaf()) continue;
    for (std::uint32_t c : {std::uint32_t(i + 1), nodes[i].offset})
      for (int a = 0; a < 3; ++a) {
        EXPECT_GE(nodes[c].lo[a], nodes[i].lo[a]);
        EXPECT_LE(nodes[c].hi[a], nodes[i].hi[a]);
      }
  }
}

TEST(Bvh, CoincidentPrimitivesStillSplitDownToLeafSizeOne) {
  Aabb b;
  b.grow(vec4(0, 0, 0));
  b.grow(vec4(1, 1, 1));
  const std::vector<Aabb> boxes(5000, b);
  const Bvh bvh = build_bvh(boxes, BvhConfig{1, Split::sah, 16});
  EXPECT_EQ(bvh.stats.leaves, 5000u);
  EXPECT_EQ(bvh.stats.max_leaf_prims, 1u);
  EXPECT_LT(bvh.stats.max_depth, kMaxBvhDepth);
}

TEST(Bvh, DepthStaysBoundedOnPathologicalClustering) {
  // Centroids at 2^-k: every midpoint split peels off one primitive.
  std::vector<Aabb> boxes;
  for (int k = 0; k < 3000; ++k) {
    Aabb b;
    const float x = std::ldexp(1.0f, -(k % 120));
    b.grow(vec4(x, 0, 0));
    b.grow(vec4(x, 1e-3f, 1e-3f));
    boxes.push_back(b);
  }
  const Bvh bvh = build_bvh(boxes, BvhConfig{1, Split::midpoint, 16});
  EXPECT_LT(bvh.stats.max_depth, kMaxBvhDepth);
  EXPECT_EQ(bvh.stats.leaves, 3000u);
}

TEST(Bvh, LeafLargerThanTheSceneIsOneLeafAndStillCorrect) {
  const Scene scene = test::geometry_scene({test::random_soup(200, 0.3f, 21)});
  const BvhConfig config{16384, Split::sah, 16};
  const Accel acc = Accel::build(scene, config);
  EXPECT_EQ(acc.stats.nodes, 1u);
  EXPECT_TRUE(acc.wide<4>().root & kLeaf || acc.wide<8>().root & kLeaf ||
              acc.wide<16>().root & kLeaf);  // one leaf: the root
  expect_closest_equals_brute_force(scene, config, test::random_rays(acc, 5000, 22));
}

TEST(Bvh, EmptySceneHasNoNodesAndRaysMiss) {
  const Scene scene = test::geometry_scene({});
  for (Isa isa : test::runnable_isas()) {
    const Accel acc = Accel::build(scene, BvhConfig{}, isa);
    EXPECT_TRUE(acc.blocks.empty());
    EXPECT_FALSE(trace_closest(acc, Ray(vec4(0, 0, 0), vec4(0, 0, -1))).found());
    EXPECT_FALSE(trace_occluded(acc, Ray(vec4(0, 0, 0), vec4(0, 0, -1)), kInfinity));
  }
}

TEST(Bvh, BuilderRejectsAbsurdConfiguration) {
  EXPECT_THROW(build_bvh({}, BvhConfig{0, Split::sah, 16}), Error);
  EXPECT_THROW(build_bvh({}, BvhConfig{4, Split::sah, 1}), Error);
  static_assert(sizeof(BvhNode) == 32);
}

TEST(Bvh, EveryTriangleSitsInOneBlockLaneWithItsExactVerticesInTheScenesFaceOrder) {
  const Mesh soup = test::random_soup(1000, 0.2f, 31);
  const Scene scene = test::geometry_scene({soup});
  const Accel acc = Accel::build(scene, BvhConfig{8, Split::sah, 16});
  ASSERT_EQ(acc.tris.size(), soup.faces.size());
  for (std::size_t k = 0; k < soup.faces.size(); ++k) {  // triangle k is face k
    const auto& f = soup.faces[k];
    EXPECT_TRUE(acc.tris[k].v0 == soup.positions[f[0]] && acc.tris[k].v1 == soup.positions[f[1]] &&
                acc.tris[k].v2 == soup.positions[f[2]]) << k;
  }
  std::vector<int> seen(acc.tris.size());
  for (const TriangleBlock& b : acc.blocks)
    for (int l = 0; l < 4; ++l) {
      const std::uint32_t p = b.prim_of(l);
      if (p == TriangleBlock::kNoPrim) continue;
      ASSERT_LT(p, acc.tris.size());
      ++seen[p];
      for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(b.v0[a][l], acc.tris[p].v0[a]);
        EXPECT_EQ(b.v1[a][l], acc.tris[p].v1[a]);
        EXPECT_EQ(b.v2[a][l], acc.tris[p].v2[a]);
      }
    }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), std::ptrdiff_t(seen.size()));
}

}  // namespace
}  // namespace rt2
