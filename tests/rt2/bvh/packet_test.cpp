// Packets (rt2/kernel/packet_traverse.h, rt2/kernel/triangle_packet_intersect.h): a packet
// of up to 16 rays walked together must answer exactly as the single-ray kernel, bit for
// bit (t, u, v, prim), on every instruction set and with both triangle tests — coherent
// tiles that take the packet path, and the lanes that must fall back or drop out: mixed
// direction signs, NaN or zero directions, empty or NaN t_max, partly filled packets,
// grazing rays, rays through shared edges and vertices, far origins, tiny and huge scales.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "rt2/scene/shapes.h"
#include "rt2/render/trace.h"
#include "tests/rt2/test_util.h"

namespace rt2 {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// A closed mesh, a triangle soup, two spheres and a ground plane, scaled by `scale` and moved
// by `offset`.
Scene packet_scene(float scale = 1.0f, vec4 offset = vec4(0.0f)) {
  Mesh soup = test::random_soup(300, 0.4f, 31);
  Mesh ball = make_icosphere(vec4(-0.4f, 0.1f, 0.0f), 0.5f, 3, 0);
  for (Mesh* m : {&soup, &ball})
    for (vec4& p : m->positions) p = p * scale + offset;
  // The second sphere is small for its distance from the rays' origins: the one-ray test
  // takes it in double precision (sphere.h).
  Scene s = test::geometry_scene({ball, soup},
                                 {Sphere{vec4(0.5f, 0.3f, 0.2f) * scale + offset, 0.3f * scale},
                                  Sphere{vec4(-0.2f, -0.3f, 0.5f) * scale + offset, 0.03f * scale}});
  s.planes.push_back(Plane{vec4(0.0f, 1.0f, 0.0f), -(offset[1] - 1.2f * scale)});
  s.plane_materials.push_back(0);
  return s;
}

// Rays from `eye` through a width x height grid on the square [-half, half]^2 of the plane
// z = center.z, in 4 x 4 tiles: each tile is one packet (a partly filled one at the right
// and bottom edges when the grid is not a multiple of 4).
struct Batch {
  std::vector<Ray> rays;
  std::vector<float> t_max;
  std::vector<std::uint32_t> begin{0};
  std::size_t packets() const { return begin.size() - 1; }
  void close_packet() { begin.push_back(static_cast<std::uint32_t>(rays.size())); }
};

Batch tiles(vec4 eye, vec4 center, float half, int width, int height) {
  Batch b;
  for (int ty = 0; ty < height; ty += 4)
    for (int tx = 0; tx < width; tx += 4) {
      for (int y = ty; y < std::min(ty + 4, height); ++y)
        for (int x = tx; x < std::min(tx + 4, width); ++x) {
          const vec4 target = center + vec4(half * (2.0f * (x + 0.5f) / width - 1.0f),
                                            half * (1.0f - 2.0f * (y + 0.5f) / height), 0.0f);
          b.rays.emplace_back(eye, normalize(target - eye));
          b.t_max.push_back(kInfinity);
        }
      b.close_packet();
    }
  return b;
}

// The packet answers against one call of the single-ray kernel per ray, for every runnable
// instruction set, both node layouts and both tests. Returns the packets walked as packets
// (summed over runs).
struct Compared {
  std::size_t closest_mismatches = 0, occluded_mismatches = 0, hits = 0, occluded = 0;
  std::uint64_t packets = 0, packet_rays = 0;
};

Compared compare(const Scene& scene, const Batch& b, const std::string& what) {
  Compared c;
  for (Isa isa : test::runnable_isas())
    for (NodeLayout layout : {NodeLayout::plain, NodeLayout::quantized}) {
      BvhConfig config;
      config.nodes = layout;
      const Accel acc = Accel::build(scene, config, isa);
      for (bool watertight : {false, true}) {
        const TraceOptions opt{watertight};
        const std::size_t n = b.rays.size();
        std::vector<Hit> single(n), packed(n);
        std::vector<std::uint8_t> occ_single(n, 7), occ_packed(n, 7);
        trace_closest(acc, opt, b.rays.data(), b.t_max.data(), n, single.data());
        trace_occluded(acc, opt, b.rays.data(), b.t_max.data(), n, occ_single.data());
        TraversalCounts counts;
        trace_closest_packets(acc, opt, b.rays.data(), b.t_max.data(), b.begin.data(), b.packets(),
                              packed.data(), &counts);
        trace_occluded_packets(acc, opt, b.rays.data(), b.t_max.data(), b.begin.data(),
                               b.packets(), occ_packed.data(), &counts);
        for (std::size_t i = 0; i < n; ++i) {
          const bool same_hit = test::bitwise_same(single[i], packed[i]);
          const bool same_occ = occ_single[i] == occ_packed[i];
          c.closest_mismatches += !same_hit;
          c.occluded_mismatches += !same_occ;
          c.hits += single[i].found();
          c.occluded += occ_single[i];
          if (!same_hit || !same_occ) {
            ADD_FAILURE() << what << ": isa " << isa_name(isa) << " quantized "
                          << (layout == NodeLayout::quantized) << " watertight " << watertight
                          << " ray " << i << " single t " << single[i].t << " prim "
                          << single[i].prim << " occ " << int(occ_single[i]) << ", packet t "
                          << packed[i].t << " prim " << packed[i].prim << " occ "
                          << int(occ_packed[i]);
            return c;
          }
        }
        c.packets += counts.packets;
        c.packet_rays += counts.packet_rays;
      }
    }
  return c;
}

TEST(Packets, CoherentTilesWalkAsPacketsAndEqualSingleRaysBitForBit) {
  const Scene scene = packet_scene();
  const Batch b = tiles(vec4(0.1f, 0.2f, 4.0f), vec4(0.0f, 0.0f, 0.0f), 1.3f, 62, 46);
  const Compared c = compare(scene, b, "coherent tiles");
  EXPECT_EQ(c.closest_mismatches + c.occluded_mismatches, 0u);
  EXPECT_GT(c.hits, b.rays.size());  // most rays hit, on every run
  // The property under test is the packet walk: most packets must take it.
  EXPECT_GT(c.packet_rays, c.packets * 8);
  EXPECT_GT(c.packet_rays, b.rays.size() * 2);
}

TEST(Packets, ShadowRaysToALightEqualSingleRaysBitForBit) {
  const Scene scene = packet_scene();
  const Batch eye = tiles(vec4(0.0f, 0.5f, 4.0f), vec4(0.0f, 0.0f, 0.0f), 1.4f, 48, 48);
  const Accel acc = Accel::build(scene, BvhConfig{});
  std::vector<Hit> hits(eye.rays.size());
  trace_closest(acc, {}, eye.rays.data(), eye.t_max.data(), eye.rays.size(), hits.data());
  // From each primary hit (nudged off the surface) to a point light, packet by packet of
  // the primary tiles: the shadow batch of a tile, as the renderer forms it.
  const vec4 light(2.0f, 3.0f, 2.5f);
  Batch shadow;
  for (std::size_t k = 0; k < eye.packets(); ++k) {
    for (std::uint32_t i = eye.begin[k]; i < eye.begin[k + 1]; ++i) {
      if (!hits[i].found()) continue;
      const vec4 p = eye.rays[i].at(hits[i].t * 0.9999f);
      const vec4 d = light - p;
      const float len = std::sqrt(float(dot(d, d)));
      shadow.rays.emplace_back(p, d / len);
      shadow.t_max.push_back(len);
    }
    if (shadow.rays.size() > shadow.begin.back()) shadow.close_packet();
  }
  const Compared c = compare(scene, shadow, "shadow rays");
  EXPECT_EQ(c.closest_mismatches + c.occluded_mismatches, 0u);
  EXPECT_GT(c.occluded, shadow.rays.size() / 10);
  EXPECT_LT(c.occluded, shadow.rays.size() * 2 * test::runnable_isas().size() - 10);
  EXPECT_GT(c.packet_rays, c.packets * 4);
}

// Shadow rays through glass: the share of light that passes (the product of the
// transparencies crossed, 0 behind an opaque surface) of packets equals each ray's own,
// through transparent triangles, spheres (one in double precision) and the ground plane.
TEST(Packets, TransmittanceThroughGlassEqualsSingleRaysBitForBit) {
  Scene scene = packet_scene();
  const float kt[] = {0.5f, 0.7f, 0.9f, 0.8f, 0.0f};
  std::uint32_t ids[5];
  for (int i = 0; i < 5; ++i) {
    Material m;
    m.transparency = kt[i];
    ids[i] = scene.add_material("k" + std::to_string(i), m);
  }
  for (std::size_t f = 0; f < scene.meshes[0].face_materials.size(); ++f)
    scene.meshes[0].face_materials[f] = ids[0];
  for (std::size_t f = 0; f < scene.meshes[1].face_materials.size(); ++f)
    scene.meshes[1].face_materials[f] = ids[f % 7 == 0 ? 4 : 1];  // some opaque triangles
  scene.sphere_materials = {ids[2], ids[1]};
  scene.plane_materials = {ids[3]};
  // From points above the scene down through it, towards a light below the ground plane,
  // and from an eye through it: rays that cross many surfaces, or few.
  Batch b = tiles(vec4(0.2f, 3.0f, 0.3f), vec4(0.0f, 0.0f, 0.0f), 1.2f, 40, 40);
  const Batch through = tiles(vec4(0.1f, 0.2f, 4.0f), vec4(0.0f, 0.0f, 0.0f), 1.3f, 40, 40);
  for (std::size_t k = 0; k < through.packets(); ++k) {
    for (std::uint32_t i = through.begin[k]; i < through.begin[k + 1]; ++i) {
      b.rays.push_back(through.rays[i]);
      b.t_max.push_back(8.0f);
    }
    b.close_packet();
  }
  for (std::size_t i = 0; i < b.t_max.size() / 2; ++i) b.t_max[i] = 5.0f;  // below the plane
  // A packet through the small sphere (the double-precision branch), from far above it.
  const Batch small = tiles(vec4(-0.2f, 3.2f, 0.5f), vec4(-0.2f, -0.3f, 0.5f), 0.025f, 4, 4);
  for (const Ray& r : small.rays) {  // in the plane z = 0.5, through the sphere's centre row
    b.rays.push_back(r);
    b.t_max.push_back(4.0f);
  }
  b.close_packet();
  for (int i = 0; i < 5; ++i) {  // a partial last packet, the arrays ending with it
    b.rays.push_back(b.rays[i]);
    b.t_max.push_back(b.t_max[i]);
  }
  b.close_packet();
  std::size_t partial = 0, blocked = 0, free = 0;
  for (Isa isa : test::runnable_isas()) {
    const Accel acc = Accel::build(scene, BvhConfig{}, isa);
    for (bool watertight : {false, true}) {
      const TraceOptions opt{watertight};
      const std::size_t n = b.rays.size();
      std::vector<float> single(n, -1.0f), packed(n, -1.0f);
      trace_transmittance(acc, scene.materials, opt, b.rays.data(), b.t_max.data(), n,
                          single.data());
      TraversalCounts counts;
      trace_transmittance_packets(acc, scene.materials, opt, b.rays.data(), b.t_max.data(),
                                  b.begin.data(), b.packets(), packed.data(), &counts);
      std::size_t mismatches = 0;
      for (std::size_t i = 0; i < n; ++i) {
        mismatches += std::memcmp(&single[i], &packed[i], sizeof(float)) != 0;
        partial += single[i] > 0.0f && single[i] < 1.0f;
        blocked += single[i] == 0.0f;
        free += single[i] == 1.0f;
      }
      EXPECT_EQ(mismatches, 0u) << isa_name(isa) << " watertight " << watertight;
      EXPECT_GT(counts.packet_rays, n / 2) << isa_name(isa) << " watertight " << watertight;
    }
  }
  EXPECT_GT(partial, 100u);
  EXPECT_GT(blocked, 100u);
  EXPECT_GT(free, 100u);
}

// Seen along the diagonal, the largest component of a ray's direction changes from ray to
// ray inside a packet: the watertight test's axis order differs, and the packet tests its
// rays one by one at the leaves; the answers stay those of single rays.
TEST(Packets, DiagonalPacketsWithMixedAxisOrdersEqualSingleRays) {
  const Scene scene = packet_scene();
  const Batch b = tiles(vec4(2.5f, 2.5f, 2.5f), vec4(0.0f, 0.0f, 0.0f), 0.8f, 32, 32);
  std::size_t mixed = 0;
  for (std::size_t k = 0; k < b.packets(); ++k) {
    const WatertightRay first(b.rays[b.begin[k]]);
    for (std::uint32_t i = b.begin[k] + 1; i < b.begin[k + 1]; ++i)
      if (WatertightRay(b.rays[i]).kz != first.kz) {
        ++mixed;
        break;
      }
  }
  EXPECT_GE(mixed, 3u);           // the property under test: packets that mix
  EXPECT_LT(mixed, b.packets());  // and packets that do not
  const Compared c = compare(scene, b, "diagonal");
  EXPECT_EQ(c.closest_mismatches + c.occluded_mismatches, 0u);
  EXPECT_GT(c.hits, b.rays.size());
  EXPECT_GT(c.packet_rays, b.rays.size() * 2);
}

// Every kind of lane a packet must refuse, drop or carry: random packets of 1..16 rays
// mixing coherent rays with NaN, zero and infinite directions, NaN origins, w lanes that
// are -0 or 1 (outside ray.h's invariant, which the SIMD plane and sphere tests assume),
// t_max of 0, NaN, a finite bound or +inf; half the packets also get lanes that keep the
// packet from walking together (mixed direction signs, zero components).
TEST(Packets, DegenerateLanesAndPartlyFilledPacketsEqualSingleRays) {
  const Scene scene = packet_scene();
  const Batch grid = tiles(vec4(0.0f, 0.0f, 4.0f), vec4(0.0f), 1.2f, 64, 64);
  std::mt19937 rng(77);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  Batch b;
  std::size_t next = 0;
  while (next + 16 <= grid.rays.size()) {
    const int size = 1 + static_cast<int>(rng() % 16);
    const bool walkable = rng() % 2;
    for (int l = 0; l < size; ++l, ++next) {
      Ray r = grid.rays[next];
      float t_max = kInfinity;
      switch (rng() % (walkable ? 12 : 15)) {
        case 0: r.dir[rng() % 3] = kNaN; break;
        case 1: {  // an infinite component, of the same sign
          const unsigned a = rng() % 3;
          r.dir[a] = std::copysign(kInfinity, float(r.dir[a]));
          break;
        }
        case 2: r.org[rng() % 3] = kNaN; break;
        case 3: t_max = 0.0f; break;
        case 4: t_max = kNaN; break;
        case 5: t_max = 4.0f * u(rng); break;
        case 6: r.org[3] = -0.0f; break;
        case 7: r.org[3] = 1.0f; break;
        case 8: r.dir[3] = -0.0f; break;
        case 12: r.dir = test::random_direction(rng); break;  // mixed signs
        case 13: r.dir = vec4(0.0f); break;
        case 14: r.dir[rng() % 2] = 0.0f; r.dir = normalize(r.dir); break;  // axis-parallel
        default: break;
      }
      b.rays.push_back(r);
      b.t_max.push_back(t_max);
    }
    b.close_packet();
  }
  const Compared c = compare(scene, b, "degenerate lanes");
  EXPECT_EQ(c.closest_mismatches + c.occluded_mismatches, 0u);
  // Runs: every ISA, both tests, closest and occluded. About half the rays walk in packets.
  const std::size_t rays = b.rays.size() * test::runnable_isas().size() * 2 * 2;
  EXPECT_GT(c.packet_rays, rays / 4);
}

// The render kernel's packets come from its batches' columns (PacketRays::load from
// RayColumns): a packet of any lanes (not only the first ones) at any offset, its other
// entries and bounds holding junk, answers as each of its rays alone, bit for bit: closest
// hits and transmittance, rays with NaN coordinates, w lanes of -0 or 1, zero and mixed
// directions, bounds of 0, NaN or short, on every instruction set with both tests.
TEST(Packets, ColumnPacketsOfAnyLanesEqualSingleRaysBitForBit) {
  Scene scene = packet_scene();
  Material glass;
  glass.transparency = 0.6f;
  const std::uint32_t g = scene.add_material("glass", glass);
  for (std::size_t f = 0; f < scene.meshes[1].face_materials.size(); f += 2)
    scene.meshes[1].face_materials[f] = g;  // half the soup lets some light through
  const Batch grid = tiles(vec4(0.0f, 0.0f, 4.0f), vec4(0.0f), 1.2f, 64, 64);
  std::mt19937 rng(91);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  constexpr std::size_t kRays = 4096;
  // Columns of kRays + 16 entries (the last packets read 16 from their first): rays of the
  // grid, some made degenerate, the rest junk until a packet takes them.
  std::vector<float> col[8];
  for (auto& c : col) c.assign(kRays + 16, kNaN);
  std::vector<float> t_max(kRays + 16, kNaN);
  std::vector<Ray> rays(kRays);
  for (std::size_t i = 0; i < kRays; ++i) {
    Ray r = grid.rays[i % grid.rays.size()];
    float t = kInfinity;
    switch (rng() % 16) {
      case 0: r.dir[rng() % 3] = kNaN; break;
      case 1: r.org[rng() % 4] = kNaN; break;
      case 2: t = 0.0f; break;
      case 3: t = kNaN; break;
      case 4: t = 4.0f * u(rng); break;
      case 5: r.org[3] = -0.0f; break;
      case 6: r.dir[3] = 1.0f; break;
      case 7: r.dir = test::random_direction(rng); break;
      case 8: r.dir = vec4(0.0f); break;
      case 9: r.dir[rng() % 2] = 0.0f; r.dir = normalize(r.dir); break;
      default: break;
    }
    rays[i] = r;
    t_max[i] = t;
    for (int a = 0; a < 4; ++a) {
      col[a][i] = r.org[a];
      col[4 + a][i] = r.dir[a];
    }
  }
  const RayColumns columns{{col[0].data(), col[1].data(), col[2].data(), col[3].data()},
                           {col[4].data(), col[5].data(), col[6].data(), col[7].data()}};
  std::size_t checked = 0, hits = 0, partial = 0;
  for (Isa isa : test::runnable_isas()) {
    const Accel acc = Accel::build(scene, BvhConfig{}, isa);
    for (bool watertight : {false, true}) {
      const TraceOptions opt{watertight};
      std::vector<Hit> single(kRays);
      std::vector<float> passed(kRays);
      trace_closest(acc, opt, rays.data(), t_max.data(), kRays, single.data());
      trace_transmittance(acc, scene.materials, opt, rays.data(), t_max.data(), kRays,
                          passed.data());
      for (std::size_t first = 0; first + 16 <= kRays; first += 1 + rng() % 16) {
        // Mostly coherent runs of lanes, some scattered, some single.
        const std::uint32_t lanes = rng() % 3 == 0 ? std::uint32_t(rng()) & 0xFFFFu
                                    : rng() % 2   ? (1u << (1 + rng() % 16)) - 1u
                                                  : 1u << (rng() % 16);
        if (!lanes) continue;
        Hit hit[16];
        float pass[16];
        for (int l = 0; l < 16; ++l) pass[l] = -1.0f;
        trace_closest_columns(acc, opt, columns, first, lanes, t_max.data() + first, hit);
        trace_transmittance_columns(acc, scene.materials, opt, columns, first, lanes,
                                    t_max.data() + first, pass);
        for (int l = 0; l < 16; ++l) {
          if (!(lanes >> l & 1)) continue;
          const std::size_t i = first + std::size_t(l);
          ++checked;
          hits += single[i].found();
          partial += passed[i] > 0.0f && passed[i] < 1.0f;
          ASSERT_TRUE(test::bitwise_same(single[i], hit[l]))
              << isa_name(isa) << " watertight " << watertight << " ray " << i << " lane " << l
              << ": single t " << single[i].t << " prim " << single[i].prim << ", packet t "
              << hit[l].t << " prim " << hit[l].prim;
          ASSERT_EQ(std::memcmp(&passed[i], &pass[l], sizeof(float)), 0)
              << isa_name(isa) << " watertight " << watertight << " ray " << i << " lane " << l
              << ": single " << passed[i] << ", packet " << pass[l];
        }
      }
    }
  }
  EXPECT_GT(hits, checked / 3);
  EXPECT_GT(partial, 100u);
}

// A shadow ray through 24 glass panes of three transparencies (more crossings than the
// walk's order could be kept apart by sorting a fixed few): packets, single rays, every
// ISA (trees 4 and 8 wide) give the product of the sorted factors, bit for bit.
TEST(Packets, TransmittanceThroughManyPanesIsTheSortedProductWhateverTheWalk) {
  Scene scene = test::geometry_scene({});
  const float kt[] = {0.9f, 0.5f, 0.7f};
  std::uint32_t ids[3];
  for (int i = 0; i < 3; ++i) {
    Material m;
    m.transparency = kt[i];
    ids[i] = scene.add_material("pane" + std::to_string(i), m);
  }
  Mesh panes;
  for (int i = 0; i < 24; ++i) {
    const float z = -1.0f + 0.08f * float(i);
    const auto base = static_cast<std::uint32_t>(panes.positions.size());
    for (vec4 p : {vec4(-1, -1, z), vec4(1, -1, z), vec4(1, 1, z), vec4(-1, 1, z)})
      panes.positions.push_back(p);
    panes.faces.push_back({base, base + 1, base + 2});
    panes.faces.push_back({base, base + 2, base + 3});
    panes.face_materials.push_back(ids[i % 3]);
    panes.face_materials.push_back(ids[i % 3]);
  }
  scene.meshes.push_back(panes);
  Batch b = tiles(vec4(0.05f, 0.02f, 3.0f), vec4(0.0f, 0.0f, 0.0f), 0.6f, 20, 20);
  for (float& t : b.t_max) t = 8.0f;
  float sorted = 1.0f;  // 0.5^8 0.7^8 0.9^8, in that order
  for (float k : {0.5f, 0.7f, 0.9f})
    for (int n = 0; n < 8; ++n) sorted *= k;
  for (Isa isa : test::runnable_isas()) {
    const Accel acc = Accel::build(scene, BvhConfig{}, isa);
    for (bool watertight : {false, true}) {
      const std::size_t n = b.rays.size();
      std::vector<float> single(n), packed(n);
      trace_transmittance(acc, scene.materials, TraceOptions{watertight}, b.rays.data(),
                          b.t_max.data(), n, single.data());
      trace_transmittance_packets(acc, scene.materials, TraceOptions{watertight}, b.rays.data(),
                                  b.t_max.data(), b.begin.data(), b.packets(), packed.data());
      std::size_t wrong = 0;
      for (std::size_t i = 0; i < n; ++i) wrong += single[i] != sorted || packed[i] != sorted;
      EXPECT_EQ(wrong, 0u) << isa_name(isa) << " watertight " << watertight << ": "
                           << single[0] << " / " << packed[0] << " for " << sorted;
    }
  }
}

// packet_begin may give empty packets and packets of more than 16 rays: those are taken 16
// at a time, and every ray still gets its single-ray answer.
TEST(Packets, EmptyAndOversizedPacketsAnswerAsSingleRays) {
  const Scene scene = packet_scene();
  const Batch grid = tiles(vec4(0.1f, 0.2f, 4.0f), vec4(0.0f), 1.3f, 16, 8);  // 128 rays
  Batch b;
  b.rays = grid.rays;
  b.t_max = grid.t_max;
  b.begin = {0, 0, 1, 17, 17, 57, 128};  // sizes 0, 1, 16, 0, 40, 71
  const Compared c = compare(scene, b, "sizes");
  EXPECT_EQ(c.closest_mismatches + c.occluded_mismatches, 0u);
  EXPECT_GT(c.packets, 0u);
}

// Rays aimed exactly at the vertices and edge midpoints of a closed mesh, in packets: the
// watertight test must find a hit for every one, as the single-ray kernel does.
TEST(Packets, RaysThroughSharedEdgesAndVerticesEqualSingleRaysAndHitWatertight) {
  const Mesh ball = make_icosphere(vec4(0.0f), 1.0f, 2, 0);
  const Scene scene = test::geometry_scene({ball});
  const vec4 eye(0.05f, 0.1f, 5.0f);
  Batch b;
  auto add = [&](vec4 target) {
    if (float(target[2]) < 0.5f) return;  // well inside the silhouette seen from the eye
    b.rays.emplace_back(eye, normalize(target - eye));
    b.t_max.push_back(kInfinity);
    if (b.rays.size() - b.begin.back() == 16) b.close_packet();
  };
  for (const vec4& p : ball.positions) add(p);
  for (const auto& f : ball.faces)
    for (int e = 0; e < 3; ++e)
      add((ball.positions[f[e]] + ball.positions[f[(e + 1) % 3]]) * 0.5f);
  if (b.rays.size() > b.begin.back()) b.close_packet();
  const Compared c = compare(scene, b, "edges and vertices");
  EXPECT_EQ(c.closest_mismatches + c.occluded_mismatches, 0u);
  EXPECT_GT(c.packets, 0u);
  for (Isa isa : test::runnable_isas()) {
    const Accel acc = Accel::build(scene, BvhConfig{}, isa);
    std::vector<Hit> hits(b.rays.size());
    trace_closest_packets(acc, TraceOptions{true}, b.rays.data(), b.t_max.data(), b.begin.data(),
                          b.packets(), hits.data());
    std::size_t missed = 0;
    for (const Hit& h : hits) missed += !h.found();
    EXPECT_EQ(missed, 0u) << isa_name(isa);
  }
}

// Rays that graze the ground plane's height and skim a flat grid of triangles edge-on.
TEST(Packets, GrazingRaysEqualSingleRays) {
  Mesh grid;
  const int n = 12;
  for (int z = 0; z <= n; ++z)
    for (int x = 0; x <= n; ++x)
      grid.positions.push_back(vec4(-1.0f + 2.0f * x / n, 0.0f, -1.0f + 2.0f * z / n));
  for (int z = 0; z < n; ++z)
    for (int x = 0; x < n; ++x) {
      const std::uint32_t a = z * (n + 1) + x, b = a + 1, c = a + n + 1, d = c + 1;
      grid.faces.push_back({a, c, b});
      grid.faces.push_back({b, c, d});
    }
  grid.face_materials.assign(grid.faces.size(), 0);
  Scene scene = test::geometry_scene({grid, test::random_soup(100, 0.3f, 5)});
  Batch b;
  for (float height : {0.0f, 1e-7f, -1e-7f, 1e-3f}) {
    const Batch t = tiles(vec4(0.0f, height, 3.0f), vec4(0.0f, height, 0.0f), 1.0f, 16, 4);
    for (std::size_t k = 0; k < t.packets(); ++k) {
      for (std::uint32_t i = t.begin[k]; i < t.begin[k + 1]; ++i) {
        Ray r = t.rays[i];
        r.dir[1] = height == 0.0f ? 0.0f : r.dir[1];  // exactly in the plane y = 0
        b.rays.push_back(r);
        b.t_max.push_back(kInfinity);
      }
      b.close_packet();
    }
  }
  const Compared c = compare(scene, b, "grazing");
  EXPECT_EQ(c.closest_mismatches + c.occluded_mismatches, 0u);
  EXPECT_GT(c.hits, 0u);
}

// The same view of the scene scaled by 1e-4 and 1e4 and moved 1e5 away from the origin.
TEST(Packets, TinyHugeAndFarScenesEqualSingleRays) {
  struct Case {
    float scale;
    vec4 offset;
  };
  for (const Case& k : {Case{1e-4f, vec4(0.0f)}, Case{1e4f, vec4(0.0f)},
                        Case{1.0f, vec4(1e5f, -3e4f, 2e5f)}}) {
    const Scene scene = packet_scene(k.scale, k.offset);
    const Batch b = tiles(vec4(0.1f, 0.2f, 4.0f) * k.scale + k.offset, k.offset, 1.3f * k.scale,
                          32, 32);
    const std::string what = "scale " + std::to_string(k.scale) + " offset " +
                             std::to_string(float(k.offset[0]));
    const Compared c = compare(scene, b, what);
    EXPECT_EQ(c.closest_mismatches + c.occluded_mismatches, 0u) << what;
    EXPECT_GT(c.hits, b.rays.size() / 2) << what;
    EXPECT_GT(c.packets, 0u) << what;
  }
}

}  // namespace
}  // namespace rt2
