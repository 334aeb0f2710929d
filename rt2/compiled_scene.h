// rt2/compiled_scene.h — a scene made ready to render: built once, then only read, by any
// number of threads and frames.
//
// A Scene (scene.h) is the description a loader fills: a camera, materials, lights and
// geometry as the file gave them. Compiling it moves what rendering needs into one owner:
// the geometry in trace order with its acceleration structures (Accel: planes, the spheres'
// tree, the triangles' wide tree for the chosen instruction set), the materials, the
// lights and the constants of shading. The camera is not part of it: where to look from,
// at what size and with which settings is the View (view.h), chosen per frame.
#pragma once

#include <cstddef>
#include <vector>

#include "rt2/accel.h"
#include "rt2/material.h"
#include "rt2/scene.h"

namespace rt2 {

struct CompiledScene {
  Accel accel;
  std::vector<Material> materials;
  std::vector<Light> lights;
  vec4 ambient;     // I_amb
  vec4 background;  // colour of rays that hit nothing
  vec4 origin;      // where these coordinates' origin is in the world (Scene::origin)
  float offset_scale = 1.0f;  // the scene's size, for secondary-ray origins (offset.h)
  unsigned features = 0;      // features.h, for reports

  // Validates `scene` (Scene::validate) and compiles it: the trees with `config`, the
  // triangles' `bvh_width(isa)` wide.
  static CompiledScene compile(const Scene& scene, const BvhConfig& config, Isa isa = best_isa());
};

}  // namespace rt2
