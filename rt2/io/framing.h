// rt2/io/framing.h — a camera and a light placed around a bounding box, for files that
// bring none (internal).
//
// Part of the implementation of rt2/io/scene_io.h, not an API: a bare OBJ (rt2::frame_obj) and
// a glTF scene without a camera or without lights (rt2/io/gltf_scene.h) are framed the same
// way, from the box's centre and R, half its diagonal.
#pragma once

#include <string>

#include "rt2/geometry/aabb.h"
#include "rt2/scene/camera.h"
#include "rt2/scene/light.h"

namespace rt2::io {

struct Framing {
  vec4 center;
  float radius = 1.0f;  // R, half the box's diagonal
};

// The framing of `box`; throws rt2::Error "file: the <what> is too large/small to frame"
// when R is not in [1e-15, 1e15] (or the box is empty).
Framing framing_of(const std::string& file, const Aabb& box, const std::string& what);

// Looks at the centre from the front (+z), slightly above, the whole box in view (45°).
Camera framing_camera(const Framing& f);

// A white light above-front, (R, 3R, 2R) from the centre.
Light framing_light(const Framing& f);

}  // namespace rt2::io
