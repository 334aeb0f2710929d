// tests/bench/bench_instances.cpp — the two-level tree's per-frame step: the top level
// (Accel::place_instances: the instances' records, their world boxes and the tree over
// them) rebuilt for N moving instances of one small mesh, per thread count, median / min /
// max over repetitions. The instances stand on a jittered square grid, each turned about y
// and scaled; each repetition moves them all (a new frame). Prints one `key=value` line per
// measurement.
//
//   build/release/bin/bench_instances [--instances 10000,1000000] [--threads 1,2] [--reps 9]
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "rt2/bvh/accel.h"
#include "rt2/scene/scene.h"
#include "rt2/scene/shapes.h"
#include "tests/bench/bench_util.h"

namespace {

using Clock = std::chrono::steady_clock;

std::vector<long> list(const char* s) {
  std::vector<long> out;
  for (char* p = const_cast<char*>(s); *p;) {
    out.push_back(std::strtol(p, &p, 10));
    if (*p == ',') ++p;
  }
  return out;
}

// n instances of mesh 0 on a jittered grid, at time t (each slides along its own direction).
std::vector<rt2::Instance> herd(std::size_t n, double t) {
  std::vector<rt2::Instance> out(n);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto side = std::size_t(std::ceil(std::sqrt(double(n))));
  for (std::size_t i = 0; i < n; ++i) {
    rt2::Transform xf;
    const double heading = 360.0 * u(rng), speed = 0.5 * u(rng);
    xf.rotate_degrees = rt2::vec4(0.0f, float(heading + 20.0 * t), 0.0f);
    xf.scale = rt2::vec4(float(0.5 + 0.5 * u(rng)), float(0.5 + 0.5 * u(rng)), float(0.5 + 0.5 * u(rng)));
    const double a = heading * 3.14159265358979 / 180.0;
    xf.translate = rt2::vec4(float(3.0 * double(i % side) + u(rng) + speed * t * std::cos(a)), 0.0f,
                             float(3.0 * double(i / side) + u(rng) + speed * t * std::sin(a)));
    out[i].to_world = rt2::affine_of(xf);
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<long> counts = {10000, 1000000}, threads = {1, 2};
  int reps = 9;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--instances") counts = list(argv[i + 1]);
    else if (a == "--threads") threads = list(argv[i + 1]);
    else if (a == "--reps") reps = std::max(1, std::atoi(argv[i + 1]));
    else {
      std::fprintf(stderr, "bench_instances: unknown option %s\n", a.c_str());
      return 2;
    }
  }
  rt2::Scene scene;
  scene.add_material("grey", rt2::Material{});
  scene.instanced_meshes.push_back(rt2::make_chair(0));
  std::printf("mesh=chair tris=%zu reps=%d max_threads=%d\n",
              scene.instanced_meshes[0].triangle_count(), reps, omp_get_max_threads());
  for (long n : counts) {
    scene.instances = herd(std::size_t(n), 0.0);
    rt2::Accel acc = rt2::Accel::build(scene, rt2::BvhConfig{});
    for (long t : threads) {
      std::vector<double> ms;
      for (int r = 0; r < reps; ++r) {
        const std::vector<rt2::Instance> moved = herd(std::size_t(n), 1.0 + r);
        const auto t0 = Clock::now();
        acc.place_instances(moved, int(t));
        ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
      }
      std::printf("top_level_rebuild instances=%ld threads=%ld median_ms=%.3f min_ms=%.3f "
                  "max_ms=%.3f bytes=%zu\n",
                  n, t, bench::median(ms), *std::min_element(ms.begin(), ms.end()),
                  *std::max_element(ms.begin(), ms.end()), acc.bvh_bytes());
      std::fflush(stdout);
    }
  }
  return 0;
}
