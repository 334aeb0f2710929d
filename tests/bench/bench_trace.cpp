// tests/bench/bench_trace.cpp — rays per second of rt2's batch queries (rt2/render/trace.h)
// on one OBJ mesh and, when built with Debian's libembree-dev (RT2_HAVE_EMBREE), of Embree 3
// on the same triangles and the same ray arrays, interleaved run by run.
//
//   bench_trace --obj data/meshes/bunny00.obj                 # everything
//   bench_trace --obj m.obj --sets primary,shadow --reps 3 --test fast --threads 1
//
// Prints `key=value` lines on stdout: each engine's build (time, bytes, SAH cost), then per
// ray set, engine, test and thread count the Mrays/s and how the engines' answers differ.
// The scene, the ray sets, the measurement and the output are defined below, each at its code.
#include <CLI/CLI.hpp>
#include <omp.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "mlib/fpmode.h"
#include "rt2/base/error.h"
#include "rt2/base/isa.h"
#include "rt2/geometry/offset.h"
#include "rt2/io/scene_io.h"
#include "rt2/render/trace.h"
#include "rt2/base/version.h"
#include "tests/bench/bench_util.h"
#include "tests/bench/face_locator.h"
#include "tests/bench/peak_memory.h"
#include "tests/bench/trace_runner.h"
#if defined(RT2_HAVE_EMBREE)
#include "tests/bench/embree_runner.h"
#endif

#if !defined(RT2_BENCH_ARCH)
#define RT2_BENCH_ARCH "unknown"
#endif
#if !defined(RT2_BENCH_MODE)
#define RT2_BENCH_MODE "unknown"
#endif

namespace {

// THE SCENE. The OBJ is loaded by rt2's own loader (rt2::frame_obj, rt2/io/scene_io.h),
// which also frames it; the ground plane frame_obj adds is removed, so both engines hold
// the mesh's triangles only (degenerate faces are dropped by the loader, for both). Below,
// c is the centre of the mesh's bounding box, R half its diagonal, S its largest extent
// (Scene::size(), the renderer's offset scale).
//   rt2:    Accel::build with the default BvhConfig (binned SAH, 16 bins, leaves <= 4).
//   Embree: one RTC_GEOMETRY_TYPE_TRIANGLE geometry sharing the mesh's vertex and index
//           arrays (the same floats rt2's triangles are made of), RTC_BUILD_QUALITY_MEDIUM;
//           scene flags none for test=fast, RTC_SCENE_FLAG_ROBUST for test=watertight
//           (Embree's mode against cracks between neighbouring triangles).
// --instanced: both engines trace the mesh as one instance, placed by T = a turn of 90
// degrees about y, then a translation to c: the instanced mesh is T^-1 of the mesh (in double,
// rounded to float), so the world holds the same triangles to rounding and the ray sets are
// the same. rt2: Scene::instanced_meshes and one Instance (the two-level tree); Embree: the
// mesh's scene, committed, in an RTC_GEOMETRY_TYPE_INSTANCE of a top scene with the same
// flags (its build time is both commits).

using bench::D3;
using bench::RaySet;
using bench::Runner;
using rt2::Hit;
using rt2::kInfinity;
using rt2::Ray;
using rt2::vec4;

constexpr std::uint32_t kIncoherentSeed = 20240601;
constexpr double kRelTol = 1e-4;  // "within a relative 1e-4" of the disagreement report
constexpr double kAbsTol = 1e-6;  // times S: distances closer than this are the same

// --- ray sets -------------------------------------------------------------------------

// THE RAY SETS (every engine traces the same arrays, in the same order):
//   primary     one ray per pixel centre of a W x H image (default 1024 x 768; W and H
//               multiples of 4) from frame_obj's camera: at c + (0, 0.3 R, 2.2 R) looking
//               at c, up +y, 45 degree vertical field of view. Stored in 4 x 4 pixel tiles,
//               tiles in row-major order, pixels row-major inside a tile; t_max = +inf.
//   incoherent  2^20 rays (--rays); origin uniform in the mesh bounds, direction uniform on
//               the sphere, from std::mt19937 seeded 20240601 and this mapping (no std
//               distribution, so the rays are the same with any standard library):
//                 U() = (rng() >> 8) * 2^-24, uniform in [0, 1), drawn in this order:
//                 org = lo + (U(), U(), U()) * (hi - lo)   (x, y, z in turn)
//                 z = 1 - 2 U(), phi = 2 pi U(), r = sqrt(max(0, 1 - z^2)),
//                 dir = normalize((r cos phi, r sin phi, z) computed in double, rounded
//                 to float);
//               t_max = +inf.
//   shadow      one ray per primary ray that hits the mesh (rt2's watertight closest hit),
//               in the primary order, towards the point light L = c + (R, 3 R, 2 R) (above,
//               right and in front: frame_obj's light). Origin o = rt2::offset_ray_origin(p,
//               n, S) as rt2's renderer does, where p is the hit point computed from the
//               hit's barycentrics on the hit triangle and n the triangle's unit geometric
//               normal turned towards the primary ray's origin; dir = (L - o) / |L - o|,
//               t_max = |L - o|. Any hit.
//               Faces turned away from the light are included (they occlude themselves).
//   reflection  one ray per primary hit, same origin o; dir = d - 2 n (n . d), the mirror
//               direction of the primary direction d about n (rt2's reflect); closest hit,
//               t_max = +inf.

RaySet primary_set(const rt2::Camera& cam, int w, int h) {
  RaySet s;
  s.name = "primary";
  s.rays.reserve(std::size_t(w) * h);
  for (int ty = 0; ty < h; ty += 4)
    for (int tx = 0; tx < w; tx += 4) {
      s.tile_begin.push_back(std::uint32_t(s.rays.size()));
      for (int ly = 0; ly < 4; ++ly)
        for (int lx = 0; lx < 4; ++lx) {
          s.rays.push_back(cam.ray(float(tx + lx) + 0.5f, float(ty + ly) + 0.5f, w, h));
          s.lane.push_back(std::uint8_t(4 * ly + lx));
        }
    }
  s.tile_begin.push_back(std::uint32_t(s.rays.size()));
  s.t_max.assign(s.rays.size(), kInfinity);
  return s;
}

float unit_float(std::mt19937& rng) { return float(rng() >> 8) * 0x1p-24f; }

RaySet incoherent_set(const rt2::Aabb& box, std::size_t n) {
  RaySet s;
  s.name = "incoherent";
  std::mt19937 rng(kIncoherentSeed);
  s.rays.reserve(n);
  const vec4 extent = box.extent();
  for (std::size_t i = 0; i < n; ++i) {
    vec4 org;
    for (int a = 0; a < 3; ++a) org[a] = box.lo[a] + unit_float(rng) * extent[a];
    org[3] = 0.0f;
    const double z = 1.0 - 2.0 * double(unit_float(rng));
    const double phi = 2.0 * std::numbers::pi * double(unit_float(rng));
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const vec4 dir = normalize(vec4(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z)));
    s.rays.emplace_back(org, dir);
  }
  s.t_max.assign(n, kInfinity);
  return s;
}

// Where secondary rays start: one per primary hit, on the face under the hit.
struct SurfaceHits {
  std::vector<std::uint32_t> ray;  // index of the primary ray
  std::vector<vec4> origin;        // offset_ray_origin(p, n, S)
  std::vector<vec4> normal;        // unit face normal towards the primary ray's origin
};

SurfaceHits surface_hits(const RaySet& primary, const std::vector<Hit>& hits,
                         const rt2::Accel& acc, float scale) {
  SurfaceHits s;
  for (std::uint32_t i = 0; i < primary.size(); ++i) {
    if (!hits[i].found()) continue;
    const Ray& r = primary.rays[i];
    // As rt2's renderer does (the render kernel, rt2/kernel/): the point from the
    // barycentrics, the face normal turned towards the ray's origin.
    const rt2::Triangle& tri = acc.tris[rt2::prim_index(hits[i].prim)];
    vec4 n = normalize(tri.n);
    if (float(dot(n, r.dir)) > 0.0f) n = -n;
    s.ray.push_back(i);
    s.origin.push_back(rt2::offset_ray_origin(tri.point(hits[i].u, hits[i].v), n, scale));
    s.normal.push_back(n);
  }
  return s;
}

// The coherent packets of a set made of some of the primary rays: tile by tile, the rays
// whose primary ray was in that tile, in the same lane.
void tiles_from_primary(const RaySet& primary, const std::vector<std::uint32_t>& from,
                        RaySet& s) {
  std::size_t k = 0;
  for (std::size_t t = 0; t < primary.tiles(); ++t) {
    s.tile_begin.push_back(std::uint32_t(k));
    while (k < from.size() && from[k] < primary.tile_begin[t + 1]) {
      s.lane.push_back(primary.lane[from[k]]);
      ++k;
    }
  }
  s.tile_begin.push_back(std::uint32_t(k));
}

RaySet shadow_set(const RaySet& primary, const SurfaceHits& sh, const vec4& light) {
  RaySet s;
  s.name = "shadow";
  s.occlusion = true;
  for (std::size_t k = 0; k < sh.ray.size(); ++k) {
    const vec4 to = light - sh.origin[k];
    const float dist = std::sqrt(float(dot(to, to)));
    s.rays.emplace_back(sh.origin[k], to / dist);
    s.t_max.push_back(dist);
  }
  tiles_from_primary(primary, sh.ray, s);
  return s;
}

RaySet reflection_set(const RaySet& primary, const SurfaceHits& sh) {
  RaySet s;
  s.name = "reflection";
  for (std::size_t k = 0; k < sh.ray.size(); ++k) {
    const vec4& d = primary.rays[sh.ray[k]].dir;
    const vec4& n = sh.normal[k];
    s.rays.emplace_back(sh.origin[k], vec4(d - 2.0f * n * dot(n, d)));
  }
  s.t_max.assign(s.rays.size(), kInfinity);
  return s;
}

// --- comparing answers ----------------------------------------------------------------

struct Agreement {
  std::size_t disagree = 0, edge = 0, end = 0, tdiff = 0, tdiff_edge = 0;
};

enum class Why { edge, end, none };

struct Explanation {
  Why why = Why::none;
  std::int64_t face = -1;  // the face under the hit (-1: none found)
  double edge_dist = NAN;  // distance from the ray's line to the face's nearest edge,
                           // over the face's longest edge
  double cos = NAN;        // |cos| of the angle between the ray and the face normal
};

// Distance between the line o + s d and the segment [p0, p1] (closest points of two lines,
// the segment's parameter clamped).
double line_segment_distance(D3 o, D3 d, D3 p0, D3 p1) {
  const D3 e = p1 - p0, w0 = o - p0;
  const double a = dot(d, d), b = dot(d, e), c = dot(e, e), dd = dot(d, w0), ee = dot(e, w0);
  const double denom = a * c - b * b;
  double t = denom > 1e-300 ? (a * ee - b * dd) / denom : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  const double s = (t * b - dd) / a;
  return length(w0 + s * d - t * e);
}

// Why an engine may have hit at distance t along ray r where another did not.
// `scale` is the scene size S.
Explanation explain(const Ray& r, float t, float t_max, float scale,
                    const bench::FaceLocator& faces) {
  Explanation x;
  if (!(t < kInfinity)) return x;
  const D3 o(r.org), d(r.dir);
  const auto f = faces.nearest(o + double(t) * d);
  x.face = f.face;
  if (f.face >= 0) {
    const auto face = std::uint32_t(f.face);
    const D3 a = faces.vertex(face, 0), e1 = faces.vertex(face, 1) - a,
             e2 = faces.vertex(face, 2) - a;
    const D3 b = faces.vertex(face, 1), c = faces.vertex(face, 2);
    const D3 n = cross(e1, e2);
    x.cos = std::fabs(dot(d, n)) / (length(d) * length(n));
    const double longest = std::max({length(e1), length(e2), length(c - b)});
    x.edge_dist = std::min({line_segment_distance(o, d, a, b), line_segment_distance(o, d, b, c),
                            line_segment_distance(o, d, c, a)}) /
                  longest;
    if (x.cos < kRelTol || x.edge_dist < kRelTol) x.why = Why::edge;
  }
  if (x.why == Why::none &&
      (t <= kRelTol * scale || (t_max < kInfinity && t >= (1.0 - kRelTol) * t_max)))
    x.why = Why::end;
  return x;
}

const char* why_name(Why w) { return w == Why::edge ? "edge" : (w == Why::end ? "end" : "none"); }

// Compares b's answers with a's. With `show` > 0, prints up to that many of the rays that
// differ to stderr, with what each engine answered and the explanation.
Agreement compare(const RaySet& set, const Runner& a, const Runner& b, float scale,
                  const bench::FaceLocator& faces, int show) {
  Agreement g;
  auto print = [&](std::size_t i, const char* what, float ta, float tb, const Explanation& x) {
    if (show-- <= 0) return;
    const Ray& r = set.rays[i];
    std::fprintf(stderr,
                 "bench_trace: %s %s vs %s, ray %zu: org %.9g %.9g %.9g dir %.9g %.9g %.9g "
                 "t_max %.9g: %s t=%.9g, %s t=%.9g; face %lld edge_dist %.3g cos %.3g -> %s\n",
                 set.name.c_str(), a.engine.c_str(), b.engine.c_str(), i, r.org[0], r.org[1],
                 r.org[2], r.dir[0], r.dir[1], r.dir[2], set.t_max[i], a.engine.c_str(), ta,
                 b.engine.c_str(), tb, static_cast<long long>(x.face), x.edge_dist, x.cos,
                 what);
  };
  for (std::size_t i = 0; i < set.size(); ++i) {
    const bool ha = a.answers.hit(i), hb = b.answers.hit(i);
    if (ha && hb && !set.occlusion) {
      const float ta = a.answers.hits[i].t, tb = b.answers.hits[i].t;
      if (std::fabs(ta - tb) > kRelTol * std::max(ta, tb) + kAbsTol * scale) {
        ++g.tdiff;  // one engine went past the surface the other stopped at: why?
        const Explanation x = explain(set.rays[i], std::min(ta, tb), set.t_max[i], scale, faces);
        g.tdiff_edge += x.why == Why::edge;
        print(i, (std::string("tdiff, ") + why_name(x.why)).c_str(), ta, tb, x);
      }
    }
    if (ha == hb) continue;
    ++g.disagree;
    const Runner& hitter = ha ? a : b;
    const float t = set.occlusion ? hitter.closest_one(i).t : hitter.answers.hits[i].t;
    const Explanation x = explain(set.rays[i], t, set.t_max[i], scale, faces);
    g.edge += x.why == Why::edge;
    g.end += x.why == Why::end;
    print(i, (std::string("disagree, ") + why_name(x.why)).c_str(), ha ? t : kInfinity,
          hb ? t : kInfinity, x);
  }
  return g;
}

// --- reporting --------------------------------------------------------------------------

// OUTPUT. Everything on stdout is `key=value` lines (progress goes to stderr):
//   cpu="..." hw_threads=N
//   rt2_mode=release rt2_arch=sse41 rt2_isa=avx512 rt2_width=8 chunk=4096  (rt2_isa: the ray
//       kernels' instruction set, the widest the CPU runs unless --isa forces one)
//   embree=3.13.5 embree_native_ray16=1 embree_tasking=tbb  (or embree=none / embree=off)
//   mesh=M tris=N set=build engine=rt2 threads=K reps=... build_ms_median=... ...
//       bytes=... bytes_per_tri=... peak_mb=... sah_nodes=... sah_leaves=...
//       (and engine=embree test=T lines, then ratio lines)
//   mesh=M set=S engine=E test=T threads=K rays=... mrays_median=... mrays_min=...
//       mrays_max=... hits=... [nodes_per_ray=... triangles_per_ray=...; rt2_packets adds
//       rays_in_packets=... differences=...] [Embree lines add, against rt2: disagree=...
//       disagree_edge=... disagree_end=... tdiff=... tdiff_edge=...]
//   mesh=M set=S test=T threads=K ratio=... [ratio16=...]
// ratio = rt2's median Mrays/s / Embree's (rtcIntersect1); ratio16 = rt2_packets' against
// Embree's 16-ray packets (rtcIntersect16), ratio_single_to_16 = rt2's single rays against
// them; for set=build, Embree's median build time / rt2's. Above 1: rt2 faster.
// disagree: rays where exactly one engine hits (closest) or reports occlusion (shadow);
// disagree_edge: those whose ray passes within a relative 1e-4 of an edge of the face under
// the hit (the distance between the ray's line and the nearest edge, over the face's
// longest edge, in double) or grazes the face (|cos| between ray and normal < 1e-4);
// disagree_end: the others whose hit is at t < 1e-4 S or t > (1 - 1e-4) t_max; the rest
// have no such excuse. tdiff: rays both engines hit at distances more than 1e-4 t + 1e-6 S
// apart (one went past the surface the other stopped at); tdiff_edge: those whose nearer
// hit is at an edge or grazing, as above. --show N prints up to N such rays per comparison
// to stderr.


struct Stats {
  double median = 0, min = 0, max = 0;
};

Stats stats(const std::vector<double>& v) {
  if (v.empty()) return {};
  return {bench::median(v), *std::min_element(v.begin(), v.end()),
          *std::max_element(v.begin(), v.end())};
}

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

bool contains(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

const char* test_name(bool watertight) { return watertight ? "watertight" : "fast"; }

// --- the run ----------------------------------------------------------------------------

// MEASUREMENT. Each engine traces the whole set once untimed (its answers are the ones
// compared below), then --reps timed runs, interleaved: rep 1 rt2, rep 1 rt2_packets,
// rep 1 embree, rep 1 embree16, rep 2 rt2, ... so drift hits all alike. A run is split into
// chunks of --chunk rays (4096; 256 tiles for packets) traced by oneTBB parallel_for in a
// task_arena of the given thread count (--threads, default 1 and all); FTZ and DAZ are set
// in every chunk (mlib/fpmode.h), as Embree sets them in its own threads. Mrays/s = rays /
// wall time.
//   engine=rt2       trace_closest / trace_occluded over each chunk;
//   engine=rt2_packets  trace_closest_packets / trace_occluded_packets, one packet per
//                    4 x 4 tile (primary and shadow only): the packet walk of
//                    rt2/kernel/packet_traverse.h. Its answers must equal engine=rt2's bit
//                    for bit (t, u, v, triangle): `differences` counts the rays where
//                    they do not; `rays_in_packets` the rays per set ray walked in a
//                    packet (the rest fell back to single rays);
//   engine=embree    rtcIntersect1 / rtcOccluded1 per ray, tnear = 0, tfar = t_max;
//   engine=embree16  rtcIntersect16 / rtcOccluded16 per 4 x 4 tile (primary and shadow
//                    only; a lane is invalid where the primary ray missed).
// Embree picks the widest instruction set of the CPU (rt2 is built for scons arch=...);
// --embree-config isa=sse4.2 (or avx2, ...) holds it to a narrower one.
// Build time: at each --threads count, the median of --build-reps builds (5; interleaved
// like the runs): rt2's Accel::build with OpenMP held to K threads (omp_set_num_threads),
// Embree's rtcCommitScene on a device created with "threads=K".
// Each engine's previous structure is released before its clock starts (so that freeing it
// is not timed and its pages can serve the next build), and each round of builds starts
// with the next engine (see build_and_report).
// Bytes per triangle: rt2's accel_bytes; Embree's net bytes allocated during rtcCommitScene
// (its memory monitor: BVH and leaf triangles; the shared vertex and index arrays are the
// application's). peak_mb: the largest growth of the resident set during one build, its
// scratch memory included (tests/bench/peak_memory.h; the most over the reps).
// Tree cost: rt2's sah_nodes and sah_leaves (Accel::tree_sah) are the statistics Embree
// prints for its own tree with --embree-config verbose=3 ("getAABBNodes : sah = ..." and
// "leaves : sah = ..."): the inner nodes and the leaf blocks a random line through the
// scene's box is expected to meet. Equal values mean equally good trees by the SAH.

struct Options {
  std::string obj;
  std::vector<std::string> sets;
  std::vector<bool> tests;  // watertight?
  std::vector<int> threads;
  int width = 1024, height = 768, reps = 7, build_reps = 5, show = 0;
  std::size_t incoherent_rays = std::size_t(1) << 20, chunk = 4096;
  bool embree = false;
  bool instanced = false;
  rt2::BvhConfig bvh;  // the default, but for --nodes
  std::string embree_config;  // appended to every Embree device's configuration
  rt2::Isa isa = rt2::best_isa();  // rt2's ray kernels
  // The configuration string of an Embree device: `base` plus embree_config.
  std::string device_config(const std::string& base) const {
    return base.empty() || embree_config.empty() ? base + embree_config
                                                 : base + "," + embree_config;
  }
};

#if defined(RT2_HAVE_EMBREE)
using EmbreeScene = RTCScene;
#else
using EmbreeScene = void*;  // never used
#endif

// The mesh under test and what the ray sets are made from.
struct Model {
  rt2::Scene scene;  // frame_obj's, without its ground plane: what rt2 traces
  rt2::Scene world;  // the same with the mesh in the world (the ray sets are made with it)
  std::string name;
  std::size_t tris = 0;
  rt2::Aabb box;  // the mesh's bounds
  vec4 light;
  float scale = 1.0f;  // S
  const rt2::Mesh& world_mesh() const { return world.meshes[0]; }
  // What Embree's triangle geometry holds: the mesh, or with --instanced the instanced mesh.
  const rt2::Mesh& mesh() const {
    return scene.instances.empty() ? scene.meshes[0] : scene.instanced_meshes[0];
  }
};

// --instanced: the mesh as one instance placed by a turn of 90 degrees about y, then a
// translation to the centre of its box.
void instance_the_mesh(Model& m) {
  const vec4 c = m.box.center();
  rt2::Instance in;
  in.to_world.m = {{{0, 0, 1, c[0]}, {0, 1, 0, c[1]}, {-1, 0, 0, c[2]}}};
  const rt2::Affine to_object = in.to_world.inverse();
  rt2::Mesh object = m.scene.meshes[0];
  for (vec4& p : object.positions) {
    const auto q = to_object.point({p[0], p[1], p[2]});
    p = vec4(float(q[0]), float(q[1]), float(q[2]));
  }
  object.normals.clear();
  m.scene.meshes.clear();
  m.scene.instanced_meshes = {std::move(object)};
  m.scene.instances = {in};
}

// The ray sets asked for, in the order primary, incoherent, shadow, reflection.
std::vector<RaySet> make_sets(const Options& o, const Model& m, const rt2::Accel& acc) {
  std::vector<RaySet> sets;
  const bool shadow = contains(o.sets, "shadow"), reflection = contains(o.sets, "reflection");
  RaySet primary;
  if (contains(o.sets, "primary") || shadow || reflection)
    primary = primary_set(m.world.camera, o.width, o.height);
  SurfaceHits sh;
  if (shadow || reflection) {
    std::vector<Hit> hits(primary.size());
    tbb::task_arena all;
    bench::run_chunks(all, primary.size(), o.chunk, [&](std::size_t b, std::size_t e) {
      rt2::trace_closest(acc, rt2::TraceOptions{true}, primary.rays.data() + b,
                         primary.t_max.data() + b, e - b, hits.data() + b);
    });
    sh = surface_hits(primary, hits, acc, m.scale);
  }
  if (contains(o.sets, "incoherent"))
    sets.push_back(incoherent_set(m.box, o.incoherent_rays));
  if (shadow) sets.push_back(shadow_set(primary, sh, m.light));
  if (reflection) sets.push_back(reflection_set(primary, sh));
  if (contains(o.sets, "primary")) sets.insert(sets.begin(), std::move(primary));
  return sets;
}

// Builds each engine's structure o.build_reps times on `threads` threads (interleaved; rt2's
// OpenMP team and Embree's device held to that count), prints the build lines, and returns
// rt2's Accel.
rt2::Accel build_and_report(const Options& o, const Model& m, int threads) {
  std::vector<double> rt2_ms;
  rt2::Accel acc;
  std::vector<std::vector<double>> embree_ms(2);
  std::vector<long long> embree_bytes(2, 0);
  std::size_t rt2_peak = 0, embree_peak[2] = {0, 0};  // the largest over the reps
  const int omp_threads = omp_get_max_threads();
  omp_set_num_threads(threads);  // Accel::build's parallel regions (bvh/build.cpp)
#if defined(RT2_HAVE_EMBREE)
  // Embree's TBB scheduler is capped by a process-wide tbb::global_control, which would cap
  // bench_trace's own loops too, so this device is released before any tracing (the
  // tracing device keeps the default thread count).
  const std::string config = "threads=" + std::to_string(threads);
  RTCDevice dev = o.embree ? bench::embree_device(o.device_config(config).c_str()) : nullptr;
#endif
  // One round: rt2's build, then Embree's for each test. Each round starts one build further
  // along the list (rt2 first, then Embree's first test, ...): a build that gets memory freed
  // longer ago can pay more for each fresh page than one that reuses what the build before
  // it freed, so the first build of a round may be the slow one, and no engine should
  // always be it.
  std::vector<std::function<void()>> builds;
  builds.push_back([&] {
    acc = rt2::Accel{};
    const bench::PeakMemory peak;
    const auto t0 = std::chrono::steady_clock::now();
    acc = rt2::Accel::build(m.scene, o.bvh, o.isa);
    rt2_ms.push_back(ms_since(t0));
    rt2_peak = std::max(rt2_peak, peak.bytes());
  });
#if defined(RT2_HAVE_EMBREE)
  if (dev)
    for (bool watertight : o.tests)
      builds.push_back([&, watertight] {
        RTCScene s = bench::embree_scene(dev, m.mesh(), watertight);
        bench::g_embree_bytes = 0;
        const bench::PeakMemory peak;
        const auto t1 = std::chrono::steady_clock::now();
        rtcCommitScene(s);
        if (o.instanced) s = bench::embree_instance_of(dev, s, m.scene.instances[0], watertight);
        embree_ms[watertight].push_back(ms_since(t1));
        embree_peak[watertight] = std::max(embree_peak[watertight], peak.bytes());
        embree_bytes[watertight] = bench::g_embree_bytes;
        rtcReleaseScene(s);
      });
#endif
  for (int rep = 0; rep < o.build_reps; ++rep)
    for (std::size_t j = 0; j < builds.size(); ++j) builds[(std::size_t(rep) + j) % builds.size()]();
#if defined(RT2_HAVE_EMBREE)
  if (dev) rtcReleaseDevice(dev);
#endif
  omp_set_num_threads(omp_threads);
  const Stats r = stats(rt2_ms);
  const std::size_t bytes = rt2::accel_bytes(acc);
  const rt2::WideSah sah = acc.tree_sah();
  std::printf("mesh=%s tris=%zu set=build engine=rt2 threads=%d reps=%d build_ms_median=%.2f "
              "build_ms_min=%.2f build_ms_max=%.2f bytes=%zu bytes_per_tri=%.1f peak_mb=%.1f "
              "isa=%s width=%d node_layout=%s nodes=%u leaves=%u blocks=%zu lanes_filled=%.3f "
              "sah_nodes=%.3f sah_leaves=%.3f\n",
              m.name.c_str(), m.tris, threads, o.build_reps, r.median, r.min, r.max, bytes,
              double(bytes) / double(m.tris), double(rt2_peak) / 1e6, rt2::isa_name(acc.isa),
              rt2::bvh_width(acc.isa), acc.quantized_nodes() ? "quantized" : "plain",
              acc.wide_nodes, acc.stats.leaves, acc.blocks.size(),
              double(m.tris) / (4.0 * double(acc.blocks.size())), sah.nodes, sah.leaves);
  for (bool watertight : o.tests) {
    if (embree_ms[watertight].empty()) continue;
    const Stats e = stats(embree_ms[watertight]);
    const long long eb = embree_bytes[watertight];
    std::printf("mesh=%s tris=%zu set=build engine=embree test=%s threads=%d reps=%d "
                "build_ms_median=%.2f build_ms_min=%.2f build_ms_max=%.2f bytes=%lld "
                "bytes_per_tri=%.1f peak_mb=%.1f\n",
                m.name.c_str(), m.tris, test_name(watertight), threads, o.build_reps, e.median,
                e.min, e.max, eb, double(eb) / double(m.tris),
                double(embree_peak[watertight]) / 1e6);
    std::printf("mesh=%s set=build test=%s threads=%d ratio=%.3f\n", m.name.c_str(),
                test_name(watertight), threads, r.median > 0 ? e.median / r.median : 0.0);
  }
  std::fflush(stdout);
  return acc;
}

// Traces `set` with every engine, test and thread count, and prints the lines.
void trace_and_report(const Options& o, const Model& m, const RaySet& set,
                      const rt2::Accel& acc,
                      [[maybe_unused]] const EmbreeScene* embree_scenes,
                      const bench::FaceLocator& faces,
                      std::vector<std::unique_ptr<tbb::task_arena>>& arenas) {
  for (bool watertight : o.tests) {
    // Runner indices: rt2 single rays, rt2 packets, Embree single rays, Embree packets
    // (-1: not run).
    std::vector<Runner> runners;
    int rt2p = -1, embree1 = -1, embree16 = -1;
    runners.push_back(bench::rt2_runner(acc, rt2::TraceOptions{watertight}, set, o.chunk));
    if (set.tiles()) {
      rt2p = int(runners.size());
      runners.push_back(bench::rt2_packet_runner(acc, rt2::TraceOptions{watertight}, set, o.chunk));
    }
#if defined(RT2_HAVE_EMBREE)
    if (o.embree) {
      const RTCScene scene = embree_scenes[watertight];
      embree1 = int(runners.size());
      runners.push_back(bench::embree1_runner(scene, set, o.chunk));
      if (set.tiles()) {
        embree16 = int(runners.size());
        runners.push_back(bench::embree16_runner(scene, set, o.chunk));
      }
    }
#endif
    std::size_t packet_differences = 0;
    std::vector<Agreement> agreement(runners.size());
    for (std::size_t ti = 0; ti < o.threads.size(); ++ti) {
      std::fprintf(stderr, "bench_trace: %s %s %s, %d thread(s), %zu rays, %d reps\n",
                   m.name.c_str(), set.name.c_str(), test_name(watertight), o.threads[ti],
                   set.size(), o.reps);
      for (Runner& r : runners) {
        r.mrays.clear();
        bench::run_chunks(*arenas[ti], r.units, r.chunk, r.body);  // untimed: warms, answers
      }
      if (ti == 0) {
        for (std::size_t k = 1; k < runners.size(); ++k)
          agreement[k] = compare(set, runners[0], runners[k], m.scale, faces, o.show);
        if (rt2p >= 0) packet_differences = bench::bitwise_differences(runners[0], runners[rt2p]);
      }
      for (int rep = 0; rep < o.reps; ++rep)
        for (Runner& r : runners) {
          const double seconds = bench::run_chunks(*arenas[ti], r.units, r.chunk, r.body);
          r.mrays.push_back(double(set.size()) / seconds * 1e-6);
        }
      for (std::size_t k = 0; k < runners.size(); ++k) {
        const Runner& r = runners[k];
        const Stats mr = stats(r.mrays);
        std::printf("mesh=%s set=%s engine=%s test=%s threads=%d rays=%zu mrays_median=%.3f "
                    "mrays_min=%.3f mrays_max=%.3f hits=%zu",
                    m.name.c_str(), set.name.c_str(), r.engine.c_str(), test_name(watertight),
                    o.threads[ti], set.size(), mr.median, mr.min, mr.max, r.answers.count());
        if (k == 0 || int(k) == rt2p) {  // rt2's own counters: what a ray costs it
          const rt2::TraceOptions opt{watertight};
          rt2::TraversalCounts counts;
          std::vector<std::uint8_t> occ(set.size());
          std::vector<Hit> hits(set.size());
          if (k == 0 && set.occlusion)
            rt2::trace_occluded(acc, opt, set.rays.data(), set.t_max.data(), set.size(),
                                occ.data(), &counts);
          else if (k == 0)
            rt2::trace_closest(acc, opt, set.rays.data(), set.t_max.data(), set.size(),
                               hits.data(), &counts);
          else if (set.occlusion)
            rt2::trace_occluded_packets(acc, opt, set.rays.data(), set.t_max.data(),
                                        set.tile_begin.data(), set.tiles(), occ.data(), &counts);
          else
            rt2::trace_closest_packets(acc, opt, set.rays.data(), set.t_max.data(),
                                       set.tile_begin.data(), set.tiles(), hits.data(), &counts);
          std::printf(" nodes_per_ray=%.2f triangles_per_ray=%.2f",
                      double(counts.nodes) / double(set.size()),
                      4.0 * double(counts.blocks) / double(set.size()));
          if (k > 0)
            std::printf(" rays_in_packets=%.3f differences=%zu",
                        double(counts.packet_rays) / double(set.size()), packet_differences);
        }
        if (k > 0 && int(k) != rt2p)
          std::printf(" disagree=%zu disagree_edge=%zu disagree_end=%zu tdiff=%zu "
                      "tdiff_edge=%zu",
                      agreement[k].disagree, agreement[k].edge, agreement[k].end,
                      agreement[k].tdiff, agreement[k].tdiff_edge);
        std::printf("\n");
      }
      if (embree1 >= 0) {
        const auto median = [&](int k) { return stats(runners[k].mrays).median; };
        std::printf("mesh=%s set=%s test=%s threads=%d ratio=%.3f", m.name.c_str(),
                    set.name.c_str(), test_name(watertight), o.threads[ti],
                    median(0) / median(embree1));
        if (embree16 >= 0)
          std::printf(" ratio16=%.3f ratio_single_to_16=%.3f", median(rt2p) / median(embree16),
                      median(0) / median(embree16));
        std::printf("\n");
      }
      std::fflush(stdout);
    }
  }
}

// Parses the command line into `o`; returns an exit status, or -1 to go on.
int parse(int argc, char** argv, Options& o) {
  CLI::App app{"bench_trace: rt2's batch ray queries on an OBJ mesh (and Embree 3's, when "
               "built with it); the ray sets are defined in tests/bench/bench_trace.cpp"};
  std::string sets = "primary,incoherent,shadow,reflection", test = "both";
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  std::string threads = hw > 1 ? "1," + std::to_string(hw) : "1";
  bool no_embree = false;
  app.add_option("--obj", o.obj, "the mesh (.obj)")->required()->check(CLI::ExistingFile);
  app.add_option("--sets", sets, "ray sets, comma-separated: primary, incoherent, shadow, "
                                 "reflection (default: all)");
  app.add_option("--width", o.width, "primary image width, a multiple of 4 (default 1024)")
      ->check(CLI::Range(4, 16384));
  app.add_option("--height", o.height, "primary image height, a multiple of 4 (default 768)")
      ->check(CLI::Range(4, 16384));
  app.add_option("--rays", o.incoherent_rays, "incoherent rays (default 2^20)")
      ->check(CLI::Range(std::size_t(1), std::size_t(1) << 28));
  app.add_option("--reps", o.reps, "timed runs per measurement (default 7)")
      ->check(CLI::Range(1, 1000));
  app.add_option("--build-reps", o.build_reps, "timed builds per engine (default 5)")
      ->check(CLI::Range(1, 1000));
  app.add_option("--threads", threads, "thread counts, comma-separated (default 1,N)");
  app.add_option("--test", test, "triangle test: fast, watertight or both (default both)")
      ->check(CLI::IsMember({"fast", "watertight", "both"}));
  app.add_option("--chunk", o.chunk, "rays per parallel task (default 4096; a multiple of 16)")
      ->check(CLI::Range(std::size_t(16), std::size_t(1) << 24));
  app.add_flag("--no-embree", no_embree, "rt2 only, even when built with Embree");
  app.add_flag("--instanced", o.instanced,
               "trace the mesh as one instance (a two-level tree) in both engines");
  std::string nodes = "plain";
  app.add_option("--nodes", nodes, "rt2's wide-tree nodes: plain or quantized (default plain)")
      ->check(CLI::IsMember({"plain", "quantized"}));
  std::string isa;
  app.add_option("--isa", isa, "rt2's ray kernels: sse41, avx2 or avx512 (default: the widest "
                               "this CPU runs)");
  app.add_option("--embree-config", o.embree_config,
                 "added to Embree's device configuration, e.g. isa=sse4.2 to hold Embree to "
                 "rt2's instruction set");
  app.add_option("--show", o.show, "print up to N differing rays per comparison to stderr")
      ->check(CLI::Range(0, 1000000));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;  // --help: 0; a bad command line: 2, as rt2cpr
  }
  const auto fail = [](const std::string& what) {
    std::fprintf(stderr, "bench_trace: %s\n", what.c_str());
    return 2;
  };
  if (o.width % 4 || o.height % 4) return fail("--width and --height must be multiples of 4");
  o.bvh.nodes = nodes == "quantized" ? rt2::NodeLayout::quantized : rt2::NodeLayout::plain;
  if (!isa.empty()) {
    try {
      o.isa = rt2::parse_isa(isa);
    } catch (const rt2::Error& e) {
      return fail(e.what());
    }
  }
  if (o.chunk % 16) return fail("--chunk must be a multiple of 16");
  o.sets = split(sets);
  for (const std::string& s : o.sets)
    if (!contains({"primary", "incoherent", "shadow", "reflection"}, s))
      return fail("unknown ray set '" + s + "' (primary, incoherent, shadow, reflection)");
  for (const std::string& t : split(threads)) {
    char* end = nullptr;
    const long v = std::strtol(t.c_str(), &end, 10);
    if (*end || v < 1 || v > 1024) return fail("bad thread count '" + t + "'");
    o.threads.push_back(int(v));
  }
  if (o.threads.empty() || o.sets.empty()) return fail("nothing to run");
  if (test != "watertight") o.tests.push_back(false);
  if (test != "fast") o.tests.push_back(true);
#if defined(RT2_HAVE_EMBREE)
  o.embree = !no_embree;
#endif
  return -1;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (const int status = parse(argc, argv, o); status >= 0) return status;
  mlib::set_flush_denormals();  // this thread too: it makes the rays and runs 1-thread arenas

  Model m;
  try {
    m.scene = rt2::frame_obj(o.obj);
  } catch (const rt2::Error& e) {
    std::fprintf(stderr, "bench_trace: %s\n", e.what());
    return 1;
  }
  m.scene.planes.clear();
  m.scene.plane_materials.clear();
  if (m.scene.meshes.size() != 1 || m.scene.meshes[0].faces.empty()) {
    std::fprintf(stderr, "bench_trace: %s: expected one mesh with triangles\n", o.obj.c_str());
    return 1;
  }
  m.name = std::filesystem::path(o.obj).stem().string();
  m.tris = m.mesh().faces.size();
  m.box = m.scene.bounds();
  const vec4 half = m.box.extent() * 0.5f;
  const float big_r = std::sqrt(float(dot(half, half)));
  m.light = m.box.center() + vec4(big_r, 3.0f * big_r, 2.0f * big_r);
  m.scale = m.scene.size();
  m.world = m.scene;
  if (o.instanced) instance_the_mesh(m);

  std::printf("cpu=\"%s\" hw_threads=%u\n", rt2::cpu_model().c_str(),
              std::max(1u, std::thread::hardware_concurrency()));
  std::printf("rt2_mode=%s rt2_arch=%s rt2_isa=%s rt2_width=%d chunk=%zu instanced=%d\n",
              RT2_BENCH_MODE, RT2_BENCH_ARCH, rt2::isa_name(o.isa), rt2::bvh_width(o.isa),
              o.chunk, int(o.instanced));
#if defined(RT2_HAVE_EMBREE)
  if (o.embree) {
    RTCDevice probe = bench::embree_device(o.device_config("").c_str());
    std::printf("embree=%s embree_native_ray16=%zd embree_tasking=%s embree_config=\"%s\"\n",
                RTC_VERSION_STRING,
                rtcGetDeviceProperty(probe, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED),
                rtcGetDeviceProperty(probe, RTC_DEVICE_PROPERTY_TASKING_SYSTEM) == 1 ? "tbb"
                                                                                     : "internal",
                o.embree_config.c_str());
    rtcReleaseDevice(probe);
  } else {
    std::printf("embree=off\n");
  }
#else
  std::printf("embree=none\n");
#endif
  std::fflush(stdout);
  std::fprintf(stderr, "bench_trace: %s: %zu triangles, %d builds per engine\n", m.name.c_str(),
               m.tris, o.build_reps);

  rt2::Accel acc;
  for (int t : o.threads) {  // the same tree at any count
    acc = rt2::Accel{};  // released before the next count's builds, as between reps
    acc = build_and_report(o, m, t);
  }
  EmbreeScene embree_scenes[2] = {nullptr, nullptr};
#if defined(RT2_HAVE_EMBREE)
  RTCDevice dev = o.embree ? bench::embree_device(o.device_config("").c_str()) : nullptr;
  if (dev)
    for (bool watertight : o.tests) {
      RTCScene s = bench::embree_scene(dev, m.mesh(), watertight);
      rtcCommitScene(s);
      if (o.instanced) s = bench::embree_instance_of(dev, s, m.scene.instances[0], watertight);
      embree_scenes[watertight] = s;
    }
#endif
  const bench::FaceLocator faces(m.world_mesh());
  // The ray sets come from the mesh in the world: the same rays with and without --instanced.
  const std::vector<RaySet> sets =
      make_sets(o, m, o.instanced ? rt2::Accel::build(m.world, o.bvh, o.isa) : acc);
  std::vector<std::unique_ptr<tbb::task_arena>> arenas;
  for (int t : o.threads) arenas.push_back(std::make_unique<tbb::task_arena>(t));
  for (const RaySet& set : sets) trace_and_report(o, m, set, acc, embree_scenes, faces, arenas);
#if defined(RT2_HAVE_EMBREE)
  for (RTCScene s : embree_scenes)
    if (s) rtcReleaseScene(s);
  if (dev) rtcReleaseDevice(dev);
#endif
  return 0;
}
