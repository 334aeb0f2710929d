// rt2/scene/builtin_scene.h — the thesis's test scene (thesis 5.4), built in code, no files needed.
//
// A chair mesh (make_chair, 10,816 triangles) and an analytic sphere beside it, both perfect
// mirrors, on a checkered ground plane under one white light, seen from the front right.
// A fixed, reproducible workload that needs no files: a default for the renderer, and a
// scene for tests and benchmarks.
#pragma once

#include "rt2/scene/scene.h"

namespace rt2 {

// Materials "mirror" (chair and sphere) and "floor" (the plane); the scene is validated.
Scene make_default_scene();

}  // namespace rt2
