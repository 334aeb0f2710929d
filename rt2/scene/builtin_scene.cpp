// rt2/scene/builtin_scene.cpp — the default scene: what is in it and where, in metres, y up.
//
// The chair stands at the origin facing +z; the sphere rests on the ground to its right
// (+x). The camera looks from the front right, a little above, at the middle of the pair,
// so both fill most of a 4:3 or 1:1 frame with 45 degrees of vertical field of view.
#include "rt2/scene/builtin_scene.h"

#include "rt2/scene/shapes.h"

namespace rt2 {
namespace {

// Thesis 5.4: "both objects have the same material — ideal reflection". Ka = Kd = 0 so all
// colour comes from the reflection; a white highlight keeps the light visible on them.
Material mirror_material() {
  Material m;
  m.ambient = vec4(0.0f, 0.0f, 0.0f);
  m.diffuse = vec4(0.0f, 0.0f, 0.0f);
  m.specular = vec4(0.6f, 0.6f, 0.6f);
  m.shininess = 120.0f;
  m.reflectivity = 1.0f;
  return m;
}

// A matte checkerboard of 0.25 m squares: the mirrors need something to reflect.
Material floor_material() {
  Material m;
  m.ambient = vec4(0.15f, 0.15f, 0.15f);
  m.diffuse = vec4(0.85f, 0.85f, 0.85f);
  m.diffuse2 = vec4(0.25f, 0.3f, 0.4f);
  m.checker_scale = 0.25f;
  m.specular = vec4(0.0f, 0.0f, 0.0f);
  m.reflectivity = 0.0f;
  return m;
}

}  // namespace

Scene make_default_scene() {
  Scene scene;
  scene.ambient = vec4(0.2f, 0.2f, 0.2f);
  scene.background = vec4(0.35f, 0.45f, 0.6f);
  const std::uint32_t mirror_id = scene.add_material("mirror", mirror_material());
  const std::uint32_t floor_id = scene.add_material("floor", floor_material());

  scene.meshes.push_back(make_chair(mirror_id));
  constexpr float kSphereRadius = 0.35f;
  scene.spheres.push_back({vec4(0.7f, kSphereRadius, -0.05f), kSphereRadius});
  scene.sphere_materials.push_back(mirror_id);
  scene.planes.push_back({vec4(0.0f, 1.0f, 0.0f), 0.0f});
  scene.plane_materials.push_back(floor_id);

  Light light;
  light.position = vec4(2.5f, 4.0f, 3.0f);
  light.intensity = 1.0f;
  scene.lights.push_back(light);

  // The pair spans x -0.23 .. 1.05, y 0 .. 0.96, z -0.4 .. 0.3; the camera aims near its
  // middle (tests/rt2/scene/builtin_scene_test.cpp checks that all of it is in view).
  scene.camera = Camera::look_at(vec4(1.1f, 0.98f, 1.6f), vec4(0.38f, 0.4f, 0.0f),
                                 vec4(0.0f, 1.0f, 0.0f), 45.0f);
  scene.validate();
  return scene;
}

}  // namespace rt2
