// tests/bench/bench_virtual.cpp — the thesis's section 5.8 (figures 25–26): what a virtual
// call per primitive costs, by array size N. The thesis kept its primitives behind a virtual
// base class; rt2 keeps them per kind in contiguous arrays. Two experiments, two designs
// each: `intersect` (rt2's ray/primitive tests, `virtual` against `segregated`) and `thesis`
// (the thesis's setup, `virtual` against `plain`), described at their code below.
//
// Output: CSV on stdout, `experiment,n,design,cycles_per_call_min,cycles_per_call_median`
// (TSC ticks per primitive test / per method call, over the passes), then
// overhead_pct_n100=... (intersect) and overhead_pct_n100_thesis=... (thesis): 100 *
// (virtual / other design - 1) of the medians at N = 100, nan when N = 100 was not run.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "mlib/timer.h"
#include "tests/bench/bench_util.h"
#include "rt2/geometry/plane.h"
#include "rt2/geometry/sphere.h"
#include "rt2/geometry/triangle.h"
#include "rt2/geometry/ray.h"

namespace {

using mlib::vec4;
using rt2::Ray;

constexpr float kTMin = 1e-4f;
constexpr std::uint64_t kCallsPerPass = 1u << 16;  // a pass is long next to the timer fence
constexpr std::uint64_t kMinRaysPerPass = 4;
constexpr std::size_t kRayPool = 1u << 14;

// --- intersect, design `virtual` ----------------------------------------------------------
// Experiment `intersect`: rt2's real ray/primitive tests.
// - `virtual`: `Primitive` with a pure virtual intersect(ray, t_min, t_max, t) and three
//   derived classes wrapping rt2::Triangle / rt2::Sphere / rt2::Plane and calling rt2's
//   free `intersect`; a std::vector<std::unique_ptr<Primitive>> of N heap objects (each
//   new'd separately, as the thesis did), kinds in a fixed-seed random order with the mix
//   of a mesh scene: 80 % triangles, 15 % spheres, 5 % planes (counts floor(0.15 N) and
//   floor(0.05 N), the rest triangles).
// - `segregated`: the very same N primitives as three contiguous arrays (triangles, then
//   spheres, then planes), each looped with a direct, inlined call.
// Each ray finds its nearest hit over all N primitives (t_max shrinks to the best t so
// far, as in a tracer). Both designs must find the same nearest t's; stderr says if not.
// Reading the numbers: inlined into the loop, rt2's triangle test may be compiled with a
// branch on part of its hit condition (t and u, v >= 0, before u + v <= 1), which is true
// often enough to mispredict; the out-of-line virtual version computes the whole bool
// branch-free. So at small N, where the indirect-branch predictor has learnt the
// repeating sequence of kinds, `virtual` can come out slightly faster.
struct Primitive {
  virtual bool intersect(const Ray& r, float t_min, float t_max, float& t) const = 0;
  virtual ~Primitive();
};
Primitive::~Primitive() = default;

struct TrianglePrim final : Primitive {
  rt2::Triangle tri;
  explicit TrianglePrim(const rt2::Triangle& x) : tri(x) {}
  bool intersect(const Ray& r, float t_min, float t_max, float& t) const override {
    float u, v;  // barycentrics: a tracer would keep them, the nearest-t search does not
    return rt2::intersect(tri, r, t_min, t_max, t, u, v);
  }
};

struct SpherePrim final : Primitive {
  rt2::Sphere sphere;
  explicit SpherePrim(const rt2::Sphere& x) : sphere(x) {}
  bool intersect(const Ray& r, float t_min, float t_max, float& t) const override {
    return rt2::intersect(sphere, r, t_min, t_max, t);
  }
};

struct PlanePrim final : Primitive {
  rt2::Plane plane;
  explicit PlanePrim(const rt2::Plane& x) : plane(x) {}
  bool intersect(const Ray& r, float t_min, float t_max, float& t) const override {
    return rt2::intersect(plane, r, t_min, t_max, t);
  }
};

using VirtualScene = std::vector<std::unique_ptr<Primitive>>;

// --- intersect, design `segregated` -------------------------------------------------------
struct SegregatedScene {
  std::vector<rt2::Triangle> triangles;
  std::vector<rt2::Sphere> spheres;
  std::vector<rt2::Plane> planes;
};

// --- building the N primitives --------------------------------------------------------
enum class Kind : std::uint8_t { triangle, sphere, plane };

// 80 / 15 / 5 % in a fixed-seed random order.
std::vector<Kind> kind_order(std::size_t n, std::mt19937& rng) {
  const std::size_t spheres = n * 15 / 100, planes = n * 5 / 100;
  std::vector<Kind> kinds(n, Kind::triangle);
  std::fill_n(kinds.begin(), spheres, Kind::sphere);
  std::fill_n(kinds.begin() + static_cast<std::ptrdiff_t>(spheres), planes, Kind::plane);
  std::shuffle(kinds.begin(), kinds.end(), rng);
  return kinds;
}

// One statement per coordinate: argument evaluation order is unspecified.
vec4 random_point(std::mt19937& rng, float half) {
  std::uniform_real_distribution<float> u(-half, half);
  const float x = u(rng);
  const float y = u(rng);
  const float z = u(rng);
  return vec4(x, y, z);
}

// Small triangles and spheres scattered in [-10, 10]^3; planes through random points.
struct Scenes {
  VirtualScene virt;
  SegregatedScene seg;
};

Scenes make_scenes(std::size_t n) {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<float> radius(0.2f, 1.0f);
  Scenes s;
  s.virt.reserve(n);
  for (const Kind k : kind_order(n, rng)) {
    const vec4 c = random_point(rng, 10.0f);
    if (k == Kind::triangle) {
      const vec4 a = c + random_point(rng, 1.0f);
      const vec4 b = c + random_point(rng, 1.0f);
      const vec4 d = c + random_point(rng, 1.0f);
      const rt2::Triangle tri = rt2::Triangle::make(a, b, d);
      s.seg.triangles.push_back(tri);
      s.virt.push_back(std::make_unique<TrianglePrim>(tri));
    } else if (k == Kind::sphere) {
      const rt2::Sphere sp{c, radius(rng)};
      s.seg.spheres.push_back(sp);
      s.virt.push_back(std::make_unique<SpherePrim>(sp));
    } else {
      const vec4 nrm = normalize(random_point(rng, 1.0f));
      const rt2::Plane pl{nrm, -float(dot(nrm, c))};
      s.seg.planes.push_back(pl);
      s.virt.push_back(std::make_unique<PlanePrim>(pl));
    }
  }
  return s;
}

// Rays from [-15, 15]^3 towards points of the primitives' box.
std::vector<Ray> make_rays() {
  std::mt19937 rng(7);
  std::vector<Ray> rays;
  rays.reserve(kRayPool);
  for (std::size_t i = 0; i < kRayPool; ++i) {
    const vec4 org = random_point(rng, 15.0f);
    const vec4 target = random_point(rng, 10.0f);
    rays.emplace_back(org, vec4(normalize(target - org)));
  }
  return rays;
}

// --- the timed loops (noinline: one call per lap, and easy to find in the asm) ---------
// Each returns the sum of the rays' nearest t (0 for a miss).
[[gnu::noinline]] double trace_virtual(const VirtualScene& prims, const Ray* rays,
                                       std::size_t n_rays) {
  double sum = 0.0;
  for (std::size_t i = 0; i < n_rays; ++i) {
    float best = rt2::kInfinity, t;
    for (const auto& p : prims)
      if (p->intersect(rays[i], kTMin, best, t)) best = t;
    sum += best < rt2::kInfinity ? best : 0.0f;
  }
  return sum;
}

[[gnu::noinline]] double trace_segregated(const SegregatedScene& s, const Ray* rays,
                                          std::size_t n_rays) {
  double sum = 0.0;
  for (std::size_t i = 0; i < n_rays; ++i) {
    const Ray& ray = rays[i];
    float best = rt2::kInfinity, t, u, v;
    for (const rt2::Triangle& tri : s.triangles)
      if (rt2::intersect(tri, ray, kTMin, best, t, u, v)) best = t;
    for (const rt2::Sphere& sp : s.spheres)
      if (rt2::intersect(sp, ray, kTMin, best, t)) best = t;
    for (const rt2::Plane& pl : s.planes)
      if (rt2::intersect(pl, ray, kTMin, best, t)) best = t;
    sum += best < rt2::kInfinity ? best : 0.0f;
  }
  return sum;
}

// --- thesis-style: one base, 4 derived classes; a plain class -----------------------------
// Experiment `thesis`: the setup as the thesis describes it: "one base class and 4 derived
// classes in one array; call one method on each element" (`virtual`, the kinds uniformly
// random, each object new'd) against "an array of the same length of objects of a class
// with no base, same method" (`plain`, objects stored by value). The method is trivial: an
// integer function of its argument and two members (x * m + k and three variants of the
// same cost in the other derived classes). The compiler may inline and vectorise the plain
// loop — that is part of what the virtual call costs.
struct Base {
  virtual std::uint32_t value(std::uint32_t x) const = 0;
  virtual ~Base() = default;
};

// Four methods of the same cost (one multiply, one add-like operation).
struct Derived0 final : Base {
  std::uint32_t m, k;
  Derived0(std::uint32_t m_, std::uint32_t k_) : m(m_), k(k_) {}
  std::uint32_t value(std::uint32_t x) const override { return x * m + k; }
};
struct Derived1 final : Base {
  std::uint32_t m, k;
  Derived1(std::uint32_t m_, std::uint32_t k_) : m(m_), k(k_) {}
  std::uint32_t value(std::uint32_t x) const override { return x * m - k; }
};
struct Derived2 final : Base {
  std::uint32_t m, k;
  Derived2(std::uint32_t m_, std::uint32_t k_) : m(m_), k(k_) {}
  std::uint32_t value(std::uint32_t x) const override { return (x + k) * m; }
};
struct Derived3 final : Base {
  std::uint32_t m, k;
  Derived3(std::uint32_t m_, std::uint32_t k_) : m(m_), k(k_) {}
  std::uint32_t value(std::uint32_t x) const override { return (x * m) ^ k; }
};

struct Plain {
  std::uint32_t m, k;
  std::uint32_t value(std::uint32_t x) const { return x * m + k; }
};

struct ThesisObjects {
  std::vector<std::unique_ptr<Base>> virt;
  std::vector<Plain> plain;
};

ThesisObjects make_thesis_objects(std::size_t n) {
  std::mt19937 rng(1999);
  std::uniform_int_distribution<int> kind(0, 3);
  ThesisObjects o;
  o.virt.reserve(n);
  o.plain.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t m = rng() | 1u;
    const std::uint32_t k = rng();
    switch (kind(rng)) {
      case 0: o.virt.push_back(std::make_unique<Derived0>(m, k)); break;
      case 1: o.virt.push_back(std::make_unique<Derived1>(m, k)); break;
      case 2: o.virt.push_back(std::make_unique<Derived2>(m, k)); break;
      default: o.virt.push_back(std::make_unique<Derived3>(m, k)); break;
    }
    o.plain.push_back(Plain{m, k});
  }
  return o;
}

// `sweeps` passes over the array, each with its own argument (so no sweep repeats another).
[[gnu::noinline]] std::uint32_t sweep_virtual(const std::vector<std::unique_ptr<Base>>& objs,
                                              std::uint32_t x0, std::size_t sweeps) {
  std::uint32_t acc = 0;
  for (std::size_t s = 0; s < sweeps; ++s) {
    const std::uint32_t x = x0 + static_cast<std::uint32_t>(s) * 2654435761u;
    for (const auto& o : objs) acc += o->value(x);
  }
  return acc;
}

[[gnu::noinline]] std::uint32_t sweep_plain(const std::vector<Plain>& objs, std::uint32_t x0,
                                            std::size_t sweeps) {
  std::uint32_t acc = 0;
  for (std::size_t s = 0; s < sweeps; ++s) {
    const std::uint32_t x = x0 + static_cast<std::uint32_t>(s) * 2654435761u;
    for (const Plain& o : objs) acc += o.value(x);
  }
  return acc;
}

// --- measurement ------------------------------------------------------------------------
// Timing: one mlib::Timer lap per pass; a pass is R rays x N primitives (intersect) or
// S sweeps over the N objects (thesis), with R, S chosen so that a pass makes at least
// ~2^16 calls (at least 4 rays even for the largest N). The fixed cost of an empty lap is
// subtracted. Rays (a pool of 2^14, fixed seed) and the method's argument change from
// pass to pass so nothing can be hoisted; every result goes into a checksum printed on
// stderr so nothing is dead. The objects' dynamic types come from a run-time random
// sequence, so the calls cannot be devirtualised (check: `objdump -d` shows `call *` in
// trace_virtual and sweep_virtual). The two designs' passes alternate, so drift of a
// shared, noisy machine hits both alike; each design gets one untimed warm-up pass per N.
struct Row {
  std::string experiment;
  std::size_t n;
  std::string design;
  double min, median;  // cycles per call
};

// Collects one design's passes: lap ticks minus the empty lap, per call.
class Laps {
 public:
  Laps(double hz, std::uint64_t overhead, double calls)
      : timer_(mlib::Timer::Mode::sum, hz), overhead_(overhead), calls_(calls) {}
  template <class F>
  auto time(F&& f) {
    timer_.Start();
    const auto r = f();
    timer_.Stop();
    const std::uint64_t ticks = timer_.Last() > overhead_ ? timer_.Last() - overhead_ : 0;
    per_call_.push_back(static_cast<double>(ticks) / calls_);
    return r;
  }
  Row row(const char* experiment, std::size_t n, const char* design) const {
    return {experiment, n, design, *std::min_element(per_call_.begin(), per_call_.end()),
            bench::median(per_call_)};
  }

 private:
  mlib::Timer timer_;
  std::uint64_t overhead_;
  double calls_;
  std::vector<double> per_call_;
};

std::uint64_t per_pass(std::size_t n, std::uint64_t at_least) {
  return std::max<std::uint64_t>(at_least, (kCallsPerPass + n - 1) / n);
}

struct Context {
  double hz;
  std::uint64_t overhead;
  int passes;
  double checksum = 0.0;
  std::uint64_t mismatches = 0;  // passes where the two intersect designs disagree
};

void run_intersect(std::size_t n, const std::vector<Ray>& rays, Context& ctx,
                   std::vector<Row>& out) {
  const Scenes s = make_scenes(n);
  const std::size_t n_rays = std::min<std::size_t>(per_pass(n, kMinRaysPerPass), kRayPool);
  const double calls = static_cast<double>(n_rays) * static_cast<double>(n);
  Laps virt(ctx.hz, ctx.overhead, calls), seg(ctx.hz, ctx.overhead, calls);
  ctx.checksum += trace_virtual(s.virt, rays.data(), n_rays);  // warm-up
  ctx.checksum += trace_segregated(s.seg, rays.data(), n_rays);
  for (int p = 0; p < ctx.passes; ++p) {
    // A different window of the pool every pass; both designs trace the same window.
    const Ray* r = rays.data() + (static_cast<std::size_t>(p + 1) * 1237) % (kRayPool - n_rays + 1);
    const double a = virt.time([&] { return trace_virtual(s.virt, r, n_rays); });
    const double b = seg.time([&] { return trace_segregated(s.seg, r, n_rays); });
    ctx.mismatches += a != b;
    ctx.checksum += a + b;
  }
  out.push_back(virt.row("intersect", n, "virtual"));
  out.push_back(seg.row("intersect", n, "segregated"));
}

void run_thesis(std::size_t n, Context& ctx, std::vector<Row>& out) {
  const ThesisObjects o = make_thesis_objects(n);
  const std::size_t sweeps = per_pass(n, 1);
  const double calls = static_cast<double>(sweeps) * static_cast<double>(n);
  Laps virt(ctx.hz, ctx.overhead, calls), plain(ctx.hz, ctx.overhead, calls);
  std::uint32_t acc = sweep_virtual(o.virt, 1, sweeps) + sweep_plain(o.plain, 1, sweeps);
  for (int p = 0; p < ctx.passes; ++p) {
    const std::uint32_t x0 = static_cast<std::uint32_t>(p) * 40503u + 17u;
    acc += virt.time([&] { return sweep_virtual(o.virt, x0, sweeps); });
    acc += plain.time([&] { return sweep_plain(o.plain, x0, sweeps); });
  }
  ctx.checksum += acc;
  out.push_back(virt.row("thesis", n, "virtual"));
  out.push_back(plain.row("thesis", n, "plain"));
}

void print(const Row& r) {
  std::printf("%s,%zu,%s,%.3f,%.3f\n", r.experiment.c_str(), r.n, r.design.c_str(), r.min,
              r.median);
  std::fflush(stdout);
}

// 100 * (median(virtual) / median(base) - 1) at N = 100, or nan.
double overhead_pct_n100(const std::vector<Row>& rows, const std::string& experiment,
                         const std::string& base) {
  const Row* v = nullptr;
  const Row* b = nullptr;
  for (const Row& r : rows) {
    if (r.experiment != experiment || r.n != 100) continue;
    if (r.design == "virtual") v = &r;
    if (r.design == base) b = &r;
  }
  if (!v || !b || !(b->median > 0.0)) return std::nan("");
  return 100.0 * (v->median / b->median - 1.0);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"bench_virtual: the thesis's 5.8 (figures 25-26): virtual calls per "
               "primitive against rt2's per-kind arrays, by array size"};
  std::size_t max_n = 1000000, max_n_intersect = 100000;
  int passes = 21;
  bool quick = false;
  app.add_option("--max-n", max_n, "largest array size (both experiments)")
      ->check(CLI::Range(std::size_t{10}, std::size_t{10000000}));
  app.add_option("--max-n-intersect", max_n_intersect,
                 "largest array size of the intersect experiment")
      ->check(CLI::Range(std::size_t{10}, std::size_t{10000000}));
  app.add_option("--passes", passes, "timed passes per design and size")
      ->check(CLI::Range(1, 1000));
  app.add_flag("--quick", quick, "N in {10, 100, 1000, 10^4} and 5 passes (a few seconds)");
  CLI11_PARSE(app, argc, argv);

  std::vector<std::size_t> sizes = {10,   20,   50,    100,    200,    500,    1000,
                                    2000, 5000, 10000, 100000, 1000000};
  if (quick) {
    sizes = {10, 100, 1000, 10000};
    passes = std::min(passes, 5);
  }

  const mlib::Timer probe;  // calibrates the TSC once
  Context ctx{probe.Frequency(), bench::empty_lap_ticks(probe.Frequency()), passes};
  std::fprintf(stderr,
               "bench_virtual: TSC %.3f GHz, empty lap %llu ticks subtracted, %d passes; "
               "intersect mix 80%% triangles / 15%% spheres / 5%% planes\n",
               ctx.hz * 1e-9, static_cast<unsigned long long>(ctx.overhead), passes);

  const std::vector<Ray> rays = make_rays();
  std::vector<Row> rows;
  std::printf("experiment,n,design,cycles_per_call_min,cycles_per_call_median\n");
  for (const std::size_t n : sizes) {
    if (n > max_n || n > max_n_intersect) continue;
    run_intersect(n, rays, ctx, rows);
    print(rows[rows.size() - 2]);
    print(rows.back());
  }
  for (const std::size_t n : sizes) {
    if (n > max_n) continue;
    run_thesis(n, ctx, rows);
    print(rows[rows.size() - 2]);
    print(rows.back());
  }
  std::printf("overhead_pct_n100=%.1f\n", overhead_pct_n100(rows, "intersect", "segregated"));
  std::printf("overhead_pct_n100_thesis=%.1f\n", overhead_pct_n100(rows, "thesis", "plain"));
  if (ctx.mismatches)
    std::fprintf(stderr, "bench_virtual: WARNING: the intersect designs disagreed in %llu passes\n",
                 static_cast<unsigned long long>(ctx.mismatches));
  std::fprintf(stderr, "bench_virtual: checksum %.17g\n", ctx.checksum);
  return 0;
}
