// rt2/io/framing.h — a camera and a light placed around a bounding box, for files that
// bring none.
//
// A bare OBJ (rt2::frame_obj) and a glTF scene without a camera or without lights
// (rt2/io/gltf_scene.h) are framed from the box's centre and R, half its diagonal. The
// camera looks at the box from above, in front and to the right, leaning towards the normal
// of its largest face, and keeps the bounding sphere inside both the vertical and the
// horizontal angle of the image: the scene records its bounds (Scene::framed_bounds) and
// rt2cpr fits the camera to the image's size (fit_framed_camera).
#pragma once

#include <string>

#include "rt2/geometry/aabb.h"
#include "rt2/scene/camera.h"
#include "rt2/scene/light.h"
#include "rt2/scene/scene.h"

namespace rt2::io {

struct Framing {
  Aabb box;
  vec4 center;
  float radius = 1.0f;  // R, half the box's diagonal
};

// The full vertical angle of a framed camera, in degrees.
inline constexpr float kFramingFov = 45.0f;
// The aspect (width / height) a framed camera has until it is fitted to an image: rt2cpr's
// default 800 x 600.
inline constexpr float kFramingAspect = 4.0f / 3.0f;

// The framing of `box`; throws rt2::Error "file: the <what> is too large/small to frame"
// when R is not in [1e-15, 1e15] (or the box is empty).
Framing framing_of(const std::string& file, const Aabb& box, const std::string& what);

// The unit direction from the centre towards a framed camera, every component > 0 (above,
// in front along +z, to the right along +x): (1, 1, 2) normalised for a box whose extents
// are alike, turning towards (2, 1, 1), (1, 2, 1) or (1, 1, 2) along the axis of its
// thinnest extent (the normal of its largest face) as that extent shrinks to 0 against the
// middle one. Each component is at least 1 / sqrt(6): the view is at least 24° from every
// face plane of the box.
vec4 framing_direction(const Framing& f);

// A camera on framing_direction looking at the centre, up +y, fov kFramingFov, as near as
// keeps the bounding sphere (centre, R) inside the vertical and the horizontal angle of an
// image of `aspect` (width / height, > 0).
Camera framing_camera(const Framing& f, float aspect);

// Gives `scene` framing_camera(f, kFramingAspect) and records f's box in
// Scene::framed_bounds, so that rt2::fit_framed_camera (rt2/io/scene_io.h) can fit it to an
// image.
void frame_camera(Scene& scene, const Framing& f);

// A white light above the camera's side: from the centre, 3 R up, 2 R along
// framing_direction and R to the right of a camera there.
Light framing_light(const Framing& f);

}  // namespace rt2::io
