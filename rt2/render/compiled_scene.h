// rt2/render/compiled_scene.h — a scene made ready to render: built once, then only read, by any
// number of threads and frames.
//
// A Scene (scene/scene.h) is the description a loader fills: a camera, materials, lights and
// geometry as the file gave them. Compiling it moves what rendering needs into one owner:
// the geometry in trace order with its acceleration structures (Accel: planes, the spheres'
// tree, the triangles' wide tree for the chosen instruction set), the materials, the
// lights and the constants of shading. The camera is not part of it: where to look from,
// at what size and with which settings is the View (render/settings.h), chosen per frame.
#pragma once

#include <cstddef>
#include <vector>

#include "rt2/bvh/accel.h"
#include "rt2/shading/brdf.h"
#include "rt2/shading/environment.h"
#include "rt2/scene/light.h"
#include "rt2/lights/light_bvh.h"
#include "rt2/scene/light_path.h"
#include "rt2/scene/material.h"
#include "rt2/scene/scene.h"
#include "rt2/shading/texture.h"

namespace rt2 {

struct CompiledScene {
  Accel accel;
  std::vector<Material> materials;
  // Per material, its physically based surface (brdf.h) when it is pbr and has no texture
  // (the same at every point: prepared once here instead of per shaded point).
  std::vector<PbrSurface> pbr_surfaces;
  // Per material, Material::plain_phong() and plain_pbr() (1 or 0): read per hit by the
  // shading lanes; whether any material is plain_phong, plain_pbr.
  std::vector<std::uint8_t> plain_phong, plain_pbr;
  bool any_plain_phong = false, any_plain_pbr = false;
  // Whether no hit can spawn two secondary rays (every material Phong without transparency:
  // a transparent one refracts and reflects, any other model may spawn two): then a batch of
  // the render kernel holds at most one ray per sample.
  bool one_ray_per_sample = true;
  std::vector<Light> lights;             // where they are this frame
  LightBvh light_bvh;                    // over `lights`' spheres of influence
  std::vector<LightPath> light_paths;    // where move_lights takes each light
  Aabb light_path_bounds;                // a box holding the paths of the lights with a range
  vec4 ambient;     // I_amb
  vec4 background;  // colour of rays that hit nothing, without an environment
  TextureSet textures;  // Scene::textures, opened
  // The light from far away (Scene::environment), prefiltered; without one, a uniform
  // environment of the ambient colour (physically based materials' ambient light), and
  // rays that miss take `background`.
  Environment environment = Environment::uniform(vec4(0.0f, 0.0f, 0.0f));
  bool has_environment = false;
  vec4 origin;      // where these coordinates' origin is in the world (Scene::origin)
  float offset_scale = 1.0f;  // the scene's size, for secondary-ray origins (offset.h)
  unsigned features = 0;      // features.h, for reports

  // What compiling took, for reports (ms): the trees, the BRDF table (brdf_lut.h; made
  // once per process, 0 without physically based materials or when made before), opening
  // the textures (reading their texels and making their mip levels), and loading and
  // prefiltering the environment.
  struct Times {
    double accel_ms = 0, brdf_table_ms = 0, textures_ms = 0, environment_ms = 0;
  } times;
  // How the last place made the trees: built, refit, or refit then rebuilt (its cost grew
  // past kRebuildCostGrowth), with the refit's cost growth.
  enum class Placed { built, refit, rebuilt };
  Placed placed = Placed::built;
  double cost_growth = 1.0;

  // Validates `scene` (Scene::validate) and compiles it: the trees with `config`, the
  // triangles' `bvh_width(isa)` wide; opens its textures and loads and prefilters its
  // environment, each image checked from its header against scene.assets first (throws
  // rt2::Error "FILE: reason" when one cannot be read, is larger than
  // scene.assets.max_image_pixels, or the environment would not fit in memory).
  static CompiledScene compile(const Scene& scene, const BvhConfig& config, Isa isa = best_isa());

  // What changes when `scene` is this compiled scene's file posed at another time (an
  // animated glTF): the trees, built with `config` for `isa` as compile builds them, the
  // lights and their tree, the origin, the offset scale and the features, each as compile
  // makes it from `scene`. Materials, textures and the environment are kept (a pose does not
  // change them). With `refit` (the caller's promise that `scene` has the topology of the
  // scene placed last, same_topology), the triangle trees are refit (Accel::refit) and
  // rebuilt only when a refit tree's cost has grown past kRebuildCostGrowth; the images are
  // the same either way (a triangle's index does not depend on its tree). Never call it
  // while a frame renders.
  void place(const Scene& scene, const BvhConfig& config, Isa isa, bool refit = false);

  // The growth of a refit tree's SAH cost (Accel::refit) past which place rebuilds it. A
  // refit tree traces incoherent rays about as much slower as its cost grew (bench_refit on
  // the bunny and the 1.4M-triangle elephant, docs/performance.md): a quarter slower is
  // where a frame's tracing loses more than a refit saves over a build.
  static constexpr double kRebuildCostGrowth = 1.25;

  // Moves every light to where its path is at `seconds` (light_path.h) and rebuilds
  // the light tree with `threads` OpenMP threads (<= 0: all). Lights are the one part of a
  // compiled scene that changes between frames; never call it while a frame renders.
  LightBvh::BuildTimes move_lights(double seconds, int threads);
};

}  // namespace rt2
