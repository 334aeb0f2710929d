// rt2/compiled_scene.cpp — compiling a Scene (see compiled_scene.h).
#include "rt2/compiled_scene.h"

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
  return c;
}

}  // namespace rt2
