// rt2/render/compiled_scene.cpp — compiling a Scene (see compiled_scene.h).
#include "rt2/render/compiled_scene.h"

#include <chrono>
#include <cstdio>
#include <string>
#include <utility>

#include "rt2/base/error.h"
#include "rt2/image/image.h"
#include "rt2/image/image_io.h"
#include "rt2/shading/brdf_lut.h"

namespace rt2 {

namespace {

// Throws rt2::Error "FILE: ..." when the environment image of `header` would not fit in the
// memory available now.
void check_environment_fits(const std::string& file, const ImageHeader& header) {
  const double need = Environment::bytes_for_image(int(header.width), int(header.height));
  const double have = available_memory_bytes();
  if (need > have) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  ": a %lld x %lld environment needs %.1f GiB of memory, but only %.1f GiB are "
                  "available",
                  static_cast<long long>(header.width), static_cast<long long>(header.height),
                  need / 1073741824.0, have / 1073741824.0);
    throw Error(file + buf);
  }
}

}  // namespace

CompiledScene CompiledScene::compile(const Scene& scene, const BvhConfig& config, Isa isa) {
  CompiledScene c;
  c.place(scene, config, isa);
  using Clock = std::chrono::steady_clock;
  const auto ms_since = [](Clock::time_point t) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
  };
  c.materials = scene.materials;
  // Shadow rays pass physically based materials by their transmission (the kernel's
  // transmittance reads `transparency`; the pbr shading step never does).
  bool pbr = false;
  for (Material& m : c.materials)
    if (m.model == Shading::pbr) {
      m.transparency = m.transmission * (1.0f - m.metallic);
      pbr = true;
    }
  Clock::time_point t = Clock::now();
  if (pbr) split_sum(0.5f, 0.5f);  // the table is made here, not in the first frame
  c.pbr_surfaces.resize(c.materials.size());
  for (std::size_t i = 0; i < c.materials.size(); ++i)
    if (const Material& m = c.materials[i]; m.model == Shading::pbr)
      c.pbr_surfaces[i] = pbr_surface(m.base_color, m.metallic, m.roughness, m.transmission);
  c.times.brdf_table_ms = ms_since(t);
  c.plain_phong.resize(c.materials.size());
  c.plain_pbr.resize(c.materials.size());
  for (std::size_t i = 0; i < c.materials.size(); ++i) {
    const Material& m = c.materials[i];
    c.plain_phong[i] = m.plain_phong();
    c.plain_pbr[i] = m.plain_pbr();
    c.any_plain_phong |= m.plain_phong();
    c.any_plain_pbr |= m.plain_pbr();
    if (m.model != Shading::phong || m.transparency > 0.0f) c.one_ray_per_sample = false;
  }
  t = Clock::now();
  c.textures = TextureSet(scene.textures, scene.assets.max_image_pixels);
  c.times.textures_ms = ms_since(t);
  t = Clock::now();
  if (scene.environment) {
    const EnvironmentDesc& e = *scene.environment;
    if (e.image.empty()) {
      c.environment = Environment::sky(e.sun_direction, e.intensity, e.rotation_degrees);
    } else {
      const ImageHeader header = read_image_header(e.image, scene.assets.max_image_pixels, e.image);
      check_environment_fits(e.image, header);
      Image img = read_image(e.image, scene.assets.max_image_pixels);
      c.environment = Environment::from_image(img.width, img.height, std::move(img.rgb),
                                              e.intensity, e.rotation_degrees);
    }
    c.has_environment = true;
  } else {
    c.environment = Environment::uniform(scene.ambient);
  }
  c.times.environment_ms = ms_since(t);
  return c;
}

void CompiledScene::place(const Scene& scene, const BvhConfig& config, Isa isa, bool refit) {
  scene.validate();
  const auto t = std::chrono::steady_clock::now();
  placed = Placed::built;
  cost_growth = 1.0;
  if (refit && accel.isa == isa && !accel.trees.empty()) {
    cost_growth = accel.refit(scene, config);
    placed = Placed::refit;
  }
  if (placed == Placed::built || cost_growth > kRebuildCostGrowth) {
    if (placed == Placed::refit) placed = Placed::rebuilt;
    accel = Accel::build(scene, config, isa);
  }
  times.accel_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
  lights = scene.lights;
  ambient = scene.ambient;
  background = scene.background;
  origin = scene.origin;
  offset_scale = scene.size();
  features = scene.features();
  light_paths.clear();
  light_paths.reserve(lights.size());
  light_path_bounds = Aabb();
  for (std::size_t i = 0; i < lights.size(); ++i) {
    light_paths.emplace_back(lights[i], i, offset_scale);
    if (lights[i].has_range()) light_path_bounds.grow(light_paths.back().bounds());
  }
  light_bvh.build(lights, 0);
}

LightBvh::BuildTimes CompiledScene::move_lights(double seconds, int threads) {
  return light_bvh.move_and_build(lights, light_paths, LightPath::turn(seconds),
                                  light_path_bounds, threads);
}

}  // namespace rt2
