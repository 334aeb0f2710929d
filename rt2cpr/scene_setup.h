// rt2cpr/scene_setup.h — the scene the command line describes, shared by file renders and
// the interactive viewer: loaded, with its camera, environment and lights as the options
// say, and made ready to render from its camera.
#pragma once

#include "rt2/compiled_scene.h"
#include "rt2/scene.h"
#include "rt2cpr/options.h"

namespace rt2cpr {

// The scene of `o.scene` (the built-in one when empty), in its own coordinates, with the
// camera of --camera and the environment of --environment when given; its lights are the
// file's (set_lights sets them). Throws rt2::Error.
rt2::Scene load_scene(const Options& o);

// The total light count `lights` (< 0: the scene's own) with --light-range's ranges
// (scene.h set_light_count). Throws rt2::Error when a range is given but nothing takes it.
void set_lights(rt2::Scene& scene, int lights, const std::optional<rt2::RangeInterval>& range);

// `scene` validated, moved so that its camera is at the origin (full float precision where
// the pixels come from: Scene::origin keeps where the world's origin went) and compiled.
rt2::CompiledScene compile_at_camera(rt2::Scene& scene, const Options& o);

}  // namespace rt2cpr
