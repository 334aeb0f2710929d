// tests/bench/bench_lights.cpp — the light tree (rt2/lights/light_bvh.h) rebuilt every frame
// for N moving lights, as --animate-lights does: the time of each step (moving the lights
// and taking their bounds, the Morton codes, the radix sort, the tree) per thread count,
// median / min / max over repetitions; then point queries (a shading point's lights) and
// box queries (a cluster's list) through the tree, and box queries by brute force. The
// lights are a hall's light field (scenes/hall.toml): uniform in 30 x 9.3 x 12 units, ranges
// uniform in --range LO,HI (default 0.3); query boxes are 0.5 units wide. Prints one
// `key=value` line per measurement.
//
//   build/release/bin/bench_lights [--lights 1000000] [--range 0.3] [--reps 9] [--threads 1,2]
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "rt2/lights/light_bvh.h"
#include "rt2/scene/light_field.h"
#include "rt2/scene/light_path.h"
#include "tests/bench/bench_util.h"

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

struct Stats {
  double median, min, max;
};
Stats stats(const std::vector<double>& v) {
  return {bench::median(v), *std::min_element(v.begin(), v.end()),
          *std::max_element(v.begin(), v.end())};
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t n = 1'000'000;
  float lo = 0.3f, hi = 0.3f;
  int reps = 9;
  std::vector<int> thread_counts{1, 2};
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i], v = argv[i + 1];
    if (a == "--lights") {
      n = std::stoul(v);
    } else if (a == "--range") {
      const auto comma = v.find(',');
      lo = std::stof(v.substr(0, comma));
      hi = comma == std::string::npos ? lo : std::stof(v.substr(comma + 1));
    } else if (a == "--reps") {
      reps = std::stoi(v);
    } else if (a == "--threads") {
      thread_counts.clear();
      for (std::size_t p = 0; p < v.size();) {
        const auto q = v.find(',', p);
        thread_counts.push_back(std::stoi(v.substr(p, q - p)));
        p = q == std::string::npos ? v.size() : q + 1;
      }
    } else {
      std::fprintf(stderr, "bench_lights: unknown option %s\n", a.c_str());
      return 2;
    }
  }
  if (n == 0 || reps < 1 || !(lo > 0.0f && lo <= hi)) {
    std::fprintf(stderr, "bench_lights: need --lights >= 1, --reps >= 1, 0 < range lo <= hi\n");
    return 2;
  }
  rt2::LightField field;
  field.box.grow(rt2::vec4(-15.0f, 0.2f, -6.0f));
  field.box.grow(rt2::vec4(15.0f, 9.5f, 6.0f));
  field.range_lo = lo;
  field.range_hi = hi;
  std::vector<rt2::Light> lights(n);
  std::vector<rt2::LightPath> paths(n);
  for (std::size_t i = 0; i < n; ++i) {
    lights[i] = field.light(i);
    paths[i] = rt2::LightPath(lights[i], i, 30.0f);
  }
  rt2::Aabb path_bounds;
  for (const rt2::LightPath& p : paths) path_bounds.grow(p.bounds());
  std::printf("lights=%zu range_lo=%g range_hi=%g reps=%d max_threads=%d\n", n, lo, hi, reps,
              omp_get_max_threads());

  rt2::LightBvh bvh;
  for (int threads : thread_counts) {
    std::vector<double> lights_pass, morton, sort, tree, total;
    for (int r = 0; r <= reps; ++r) {  // repetition 0 warms up (first allocations)
      const rt2::LightBvh::BuildTimes b =
          bvh.move_and_build(lights, paths, rt2::LightPath::turn(r / 30.0), path_bounds, threads);
      if (r == 0) continue;
      lights_pass.push_back(b.lights_ms);
      morton.push_back(b.morton_ms);
      sort.push_back(b.sort_ms);
      tree.push_back(b.tree_ms);
      total.push_back(b.total_ms());
    }
    for (const auto& [name, v] : {std::pair{"move_and_bounds", &lights_pass}, {"morton", &morton},
                                  {"sort", &sort}, {"tree", &tree}, {"total", &total}}) {
      const Stats s = stats(*v);
      std::printf("light_update step=%s threads=%d median_ms=%.3f min_ms=%.3f max_ms=%.3f\n",
                  name, threads, s.median, s.min, s.max);
    }
  }
  std::printf("light_bvh levels=%zu bytes=%zu bytes_per_light=%.1f\n", bvh.levels(), bvh.bytes(),
              double(bvh.bytes()) / double(n));

  // Queries, one thread.
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const auto random_point = [&]() {
    return field.box.lo + rt2::vec4(u(rng), u(rng), u(rng)) * field.box.extent();
  };
  std::vector<std::uint32_t> out;
  const int points = 200'000;
  std::vector<rt2::vec4> ps(points);
  for (auto& p : ps) p = random_point();
  std::vector<double> per_point;
  std::size_t found = 0;
  for (int r = 0; r < reps; ++r) {
    const auto t0 = Clock::now();
    for (const auto& p : ps) {
      bvh.lights_near(p, out);
      found += out.size();
    }
    per_point.push_back(ms_since(t0) * 1e6 / points);
  }
  const Stats q = stats(per_point);
  std::printf("point_query median_ns=%.1f min_ns=%.1f max_ns=%.1f lights_per_query=%.2f\n",
              q.median, q.min, q.max, double(found) / double(points) / reps);
  const int boxes = 2000;
  std::vector<rt2::Aabb> bs(boxes);
  for (auto& b : bs) {
    const rt2::vec4 p = random_point();
    b.grow(p);
    b.grow(p + rt2::vec4(0.5f, 0.5f, 0.5f));
  }
  for (int brute = 0; brute < 2; ++brute) {
    std::vector<double> per_box;
    found = 0;
    for (int r = 0; r < (brute ? 1 : reps); ++r) {
      const auto t0 = Clock::now();
      for (const auto& b : bs) {
        if (brute)
          bvh.lights_near_brute_force(b, out);
        else
          bvh.lights_near(b, out);
        found += out.size();
      }
      per_box.push_back(ms_since(t0) * 1e3 / boxes);
    }
    const Stats s = stats(per_box);
    std::printf("box_query method=%s median_us=%.2f min_us=%.2f max_us=%.2f lights_per_box=%.2f\n",
                brute ? "brute-force" : "bvh", s.median, s.min, s.max,
                double(found) / double(boxes) / (brute ? 1 : reps));
  }
  return 0;
}
