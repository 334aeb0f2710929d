// rt2/compiled_scene.cpp — compiling a Scene (see compiled_scene.h).
#include "rt2/compiled_scene.h"

#include <chrono>

#include <omp.h>

namespace rt2 {

CompiledScene CompiledScene::compile(const Scene& scene, const BvhConfig& config, Isa isa) {
  scene.validate();
  CompiledScene c;
  c.accel = Accel::build(scene, config, isa);
  c.materials = scene.materials;
  c.lights = scene.lights;
  c.ambient = scene.ambient;
  c.background = scene.background;
  c.origin = scene.origin;
  c.offset_scale = scene.size();
  c.features = scene.features();
  c.light_paths.reserve(c.lights.size());
  for (std::size_t i = 0; i < c.lights.size(); ++i)
    c.light_paths.emplace_back(c.lights[i], i, c.offset_scale);
  c.light_bvh.build(c.lights, 0);
  return c;
}

LightBvh::BuildTimes CompiledScene::move_lights(double seconds, int threads) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t n = lights.size();
  const LightPath::Turn turn = LightPath::turn(seconds);
#pragma omp parallel for num_threads(threads > 0 ? threads : omp_get_max_threads()) schedule(static)
  for (std::size_t i = 0; i < n; ++i) lights[i].position = light_paths[i].at(turn);
  const double move_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  LightBvh::BuildTimes times = light_bvh.build(lights, threads);
  times.move_ms = move_ms;
  return times;
}

}  // namespace rt2
