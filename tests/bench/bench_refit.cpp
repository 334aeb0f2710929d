// tests/bench/bench_refit.cpp — refitting a deformed mesh's tree (Accel::refit) against
// building it afresh (Accel::build): the time of each per thread count, and, per amount of
// deformation, how much the refit tree's cost has grown (wide_sah, as Accel::refit reports
// it) and how much slower it traces than the fresh tree (1 thread, the same rays, the two
// alternated). Median / min / max over repetitions; one `key=value` line per measurement.
// The deformation bends the mesh along its height (a wave of `amount` times its size), as a
// skinned limb or a flag moves, and each repetition moves it a little (a new frame).
//
//   build/release/bin/bench_refit --obj data/meshes/refined_elephant-x16.obj
//       [--threads 1,2] [--reps 7] [--amounts 0.02,0.1,0.3,1] [--rays 200000]
//
// With --animated, a frame of an animated glTF instead: posing it (ScenePoser::at: the
// nodes, skinning and morphing) and refitting its trees (Accel::refit), per thread count,
// over `--reps` frames 1/30 s apart (scripts/make-animated-scene makes such files).
//
//   build/release/bin/bench_refit --animated anim.gltf [--threads 1,2] [--reps 60]
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
#include "rt2/io/scene_io.h"
#include "rt2/render/trace.h"
#include "rt2/scene/scene.h"
#include "tests/bench/bench_util.h"

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

std::vector<double> list(const char* s) {
  std::vector<double> out;
  for (char* p = const_cast<char*>(s); *p;) {
    out.push_back(std::strtod(p, &p));
    if (*p == ',') ++p;
  }
  return out;
}

// `scene` with its meshes bent: x moves by amount * size * sin(phase + 2 pi y / height).
rt2::Scene bent(const rt2::Scene& scene, double amount, double phase) {
  rt2::Scene out = scene;
  const rt2::Aabb box = scene.bounds();
  const double size = scene.size(), height = std::max(1e-30, double(box.extent()[1]));
  for (rt2::Mesh& m : out.meshes)
    for (rt2::vec4& p : m.positions) {
      const double y = (double(p[1]) - box.lo[1]) / height;
      p = rt2::vec4(float(p[0] + amount * size * std::sin(phase + 6.283185307179586 * y)), p[1],
                    p[2]);
    }
  return out;
}

// Rays from random points of a box 1.5 times the scene's toward random points of its
// triangles: incoherent, and most of them hit.
std::vector<rt2::Ray> rays_at(const rt2::Accel& acc, const rt2::Aabb& box, std::size_t n) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<rt2::Ray> rays;
  const rt2::vec4 c = box.center(), e = box.extent() * 0.75f;
  while (rays.size() < n) {
    const rt2::vec4 org(c[0] + e[0] * (2 * u(rng) - 1), c[1] + e[1] * (2 * u(rng) - 1),
                        c[2] + e[2] * (2 * u(rng) - 1));
    const rt2::Triangle& t = acc.tris[rng() % acc.tris.size()];
    float a = u(rng), b = u(rng);
    if (a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
    const rt2::vec4 d = t.point(a, b) - org;
    if (!(float(dot(d, d)) > 0.0f)) continue;
    rays.emplace_back(org, normalize(d));
  }
  return rays;
}

void print(const char* what, const std::string& keys, const std::vector<double>& ms) {
  std::printf("%s %s median_ms=%.3f min_ms=%.3f max_ms=%.3f\n", what, keys.c_str(),
              bench::median(ms), *std::min_element(ms.begin(), ms.end()),
              *std::max_element(ms.begin(), ms.end()));
  std::fflush(stdout);
}

// The --animated measurement.
int animated(const std::string& file, const std::vector<double>& threads, int reps) {
  rt2::ScenePoser poser;
  rt2::Scene scene;
  try {
    scene = rt2::load_scene(file, {}, {}, &poser);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_refit: %s\n", e.what());
    return 1;
  }
  if (!poser) {
    std::fprintf(stderr, "bench_refit: %s has no animation\n", file.c_str());
    return 1;
  }
  std::printf("animated=%s tris=%zu instances=%zu reps=%d max_threads=%d\n", file.c_str(),
              scene.triangle_count(), scene.instances.size(), reps, omp_get_max_threads());
  const rt2::BvhConfig config;
  for (const double t : threads) {
    omp_set_num_threads(int(t));
    rt2::Accel acc = rt2::Accel::build(scene, config);
    std::vector<double> pose, refit, both;
    double growth = 1.0;
    for (int r = 1; r <= reps; ++r) {
      auto t0 = Clock::now();
      const rt2::Scene posed = poser.at(r / 30.0);
      pose.push_back(ms_since(t0));
      t0 = Clock::now();
      growth = std::max(growth, acc.refit(posed, config, int(t)));
      refit.push_back(ms_since(t0));
      both.push_back(pose.back() + refit.back());
    }
    const std::string keys = "threads=" + std::to_string(int(t));
    print("pose", keys, pose);
    print("refit", keys, refit);
    print("pose_and_refit", keys, both);
    std::printf("max_cost_growth threads=%d growth=%.3f\n", int(t), growth);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::string obj, animated_file;
  std::vector<double> threads = {1, 2}, amounts = {0.02, 0.1, 0.3, 1.0};
  int reps = 7;
  std::size_t ray_count = 200000;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--obj") obj = argv[i + 1];
    else if (a == "--animated") animated_file = argv[i + 1];
    else if (a == "--threads") threads = list(argv[i + 1]);
    else if (a == "--amounts") amounts = list(argv[i + 1]);
    else if (a == "--reps") reps = std::max(1, std::atoi(argv[i + 1]));
    else if (a == "--rays") ray_count = std::size_t(std::max(1, std::atoi(argv[i + 1])));
    else {
      std::fprintf(stderr, "bench_refit: unknown option %s\n", a.c_str());
      return 2;
    }
  }
  if (!animated_file.empty()) return animated(animated_file, threads, reps);
  if (obj.empty()) {
    std::fprintf(stderr, "bench_refit: --obj MESH.obj or --animated FILE.gltf is required\n");
    return 2;
  }
  rt2::Scene scene;
  try {
    scene = rt2::load_scene(obj);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_refit: %s\n", e.what());
    return 1;
  }
  std::printf("mesh=%s tris=%zu reps=%d max_threads=%d\n", obj.c_str(), scene.triangle_count(),
              reps, omp_get_max_threads());
  const rt2::BvhConfig config;
  const std::vector<rt2::Scene> frames = {bent(scene, amounts.front(), 0.0),
                                          bent(scene, amounts.front(), 0.1)};
  for (double t : threads) {
    omp_set_num_threads(int(t));
    std::vector<double> build, refit;
    rt2::Accel acc = rt2::Accel::build(frames[0], config);
    for (int r = 0; r < reps; ++r) {  // alternated: build, refit, build, ...
      auto t0 = Clock::now();
      const rt2::Accel fresh = rt2::Accel::build(frames[std::size_t(r % 2)], config);
      build.push_back(ms_since(t0));
      t0 = Clock::now();
      acc.refit(frames[std::size_t((r + 1) % 2)], config, int(t));
      refit.push_back(ms_since(t0));
    }
    const std::string keys = "threads=" + std::to_string(int(t));
    print("build", keys, build);
    print("refit", keys + " amount=" + std::to_string(amounts.front()), refit);
    std::printf("refit_over_build threads=%d ratio=%.3f\n", int(t),
                bench::median(refit) / bench::median(build));
  }
  omp_set_num_threads(1);
  rt2::Accel acc = rt2::Accel::build(scene, config);
  for (double amount : amounts) {
    const rt2::Scene moved = bent(scene, amount, 0.0);
    const double growth = acc.refit(moved, config, 1);
    const rt2::Accel fresh = rt2::Accel::build(moved, config);
    const std::vector<rt2::Ray> rays = rays_at(fresh, moved.bounds(), ray_count);
    const std::vector<float> t_max(rays.size(), rt2::kInfinity);
    std::vector<rt2::Hit> hits(rays.size());
    std::vector<double> refit_ms, fresh_ms;
    for (int r = 0; r < reps; ++r) {
      auto t0 = Clock::now();
      rt2::trace_closest(acc, {}, rays.data(), t_max.data(), rays.size(), hits.data());
      refit_ms.push_back(ms_since(t0));
      t0 = Clock::now();
      rt2::trace_closest(fresh, {}, rays.data(), t_max.data(), rays.size(), hits.data());
      fresh_ms.push_back(ms_since(t0));
    }
    std::printf("quality amount=%.3f cost_growth=%.3f trace_refit_ms=%.2f trace_fresh_ms=%.2f "
                "trace_ratio=%.3f\n",
                amount, growth, bench::median(refit_ms), bench::median(fresh_ms),
                bench::median(refit_ms) / bench::median(fresh_ms));
    std::fflush(stdout);
  }
  return 0;
}
