// rt2/scene/scene.h — a scene as described: camera, lights, materials and geometry.
//
// This is the description a loader fills; rt2::Accel compiles its geometry into BVH order
// for rendering. Planes are unbounded and stay outside the BVH.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "rt2/base/asset_policy.h"
#include "rt2/scene/animation.h"
#include "rt2/scene/camera.h"
#include "rt2/scene/features.h"
#include "rt2/scene/instance.h"
#include "rt2/geometry/plane.h"
#include "rt2/geometry/sphere.h"
#include "rt2/scene/light.h"
#include "rt2/scene/light_field.h"
#include "rt2/scene/material.h"
#include "rt2/scene/mesh.h"

namespace rt2 {

// An image a material samples (rt2/shading/texture.h): a file, or an image held in the scene file
// itself (glTF's embedded images), whose bytes are `data`.
struct TextureDesc {
  std::string path;  // the file; for an embedded image, a name for messages ("x.glb:image 2")
  std::string data;  // an embedded image's file bytes (PNG, JPEG, ...); empty for a file
  bool srgb = true;  // whether its values are sRGB-encoded colours (else linear data)
};

// The light arriving from far away in every direction (rt2/shading/environment.h): the background
// of rays that miss, and the image-based light of physically based materials.
struct EnvironmentDesc {
  // An equirectangular HDR image (.hdr, .exr, ...); empty: a procedural sky.
  std::string image;
  float intensity = 1.0f;         // scales the image or sky (>= 0)
  float rotation_degrees = 0.0f;  // turns it about the up (y) axis
  vec4 sun_direction{0.3f, 0.8f, 0.5f};  // the sky's sun (normalized on use)
};

struct Scene {
  Camera camera;
  // Set when the loader placed `camera` because the file gives none (a bare OBJ, a glTF
  // without a camera): the bounds it frames, in the coordinates as loaded (recenter_on_camera
  // does not move them). rt2/io/framing.h fit_framed_camera fits the camera to an image's
  // width and height; empty: the file's own camera, which nothing changes.
  std::optional<Aabb> framed_bounds;
  vec4 ambient{0.2f, 0.2f, 0.2f};      // I_amb, the ambient light
  vec4 background{0.0f, 0.0f, 0.0f};  // colour of rays that hit nothing
  // Where this scene's coordinate origin is in the world: 0 as loaded, the camera's old
  // position after recenter_on_camera. Procedural textures (the checker) use world
  // coordinates, p + origin, so recentring does not move them.
  vec4 origin{0.0f, 0.0f, 0.0f};

  std::vector<Material> materials;
  std::vector<std::string> material_names;  // parallel to materials
  std::vector<TextureDesc> textures;        // what Material::*_texture index
  // The environment; none: rays that miss take `background`, and physically based
  // materials take `ambient` as light from every direction.
  std::optional<EnvironmentDesc> environment;
  std::vector<Light> lights;
  // Where extra lights go (set_light_count): the scene's light field, if it has one. Its
  // lights are lights[field.first ...].
  std::optional<LightField> light_field;
  // What the scene's files could refer to and how large its images may be: the policy it was
  // loaded under, which compiling applies to its textures and environment.
  AssetPolicy assets;

  std::vector<Sphere> spheres;
  std::vector<std::uint32_t> sphere_materials;
  std::vector<Plane> planes;
  std::vector<std::uint32_t> plane_materials;
  std::vector<Mesh> meshes;
  // Meshes placed only by `instances`, in their own coordinates: each is traced through one
  // tree that all its instances share (rt2/bvh/accel.h), its triangles stored once.
  std::vector<Mesh> instanced_meshes;
  std::vector<Instance> instances;

  std::size_t degenerate_triangles = 0;  // dropped by the loaders, reported by rt2cpr
  // The animations of the file the scene was loaded from (glTF; none: it does not move),
  // and the pose it was loaded in: animations[animation] at `seconds` (-1: none).
  std::vector<AnimationSummary> animations;
  int animation = -1;
  double seconds = 0.0;

  // Adds a material and returns its index.
  std::uint32_t add_material(const std::string& name, const Material& m);
  // Index of the material called `name`, or -1.
  int find_material(const std::string& name) const;

  // The triangles stored: the meshes' and the instanced meshes' (each once).
  std::size_t triangle_count() const;
  // The triangles in the world: the meshes' and every instance's.
  std::size_t placed_triangle_count() const;
  // Bounds of the bounded geometry (spheres, meshes, instances); empty if there is none.
  Aabb bounds() const;
  // The scene's size for the ray-origin offset (rt2/geometry/offset.h): the largest extent
  // of its bounded geometry, or 1 when it has none (planes only).
  float size() const;
  // The feature bits this scene needs (see features.h), given how many lights are used.
  unsigned features(std::size_t light_count) const;
  unsigned features() const { return features(lights.size()); }
  // Throws rt2::Error for anything a renderer cannot use: non-finite numbers, material
  // indices out of range, radius <= 0, zero plane normals.
  void validate() const;
};

// Whether `b`'s triangles are `a`'s, perhaps moved: the same meshes and instanced meshes
// with the same faces, face materials, and normals and texture coordinates present or
// absent alike (their positions, normals and coordinates may differ). Then trees built over
// `a` can be refit to `b` (Accel::refit).
bool same_topology(const Scene& a, const Scene& b);

// Moves the whole scene by -camera position, so that the camera sits at the origin.
// Rendering is invariant under translation, but float precision is not: a scene a
// million units from the origin has an ulp of 0.0625 there, which swallows small objects
// and the ray-origin offsets of secondary rays (rt2/geometry/offset.h). Near the camera,
// where the pixels come from, camera-relative coordinates keep full precision; input
// coordinates that are exact floats stay exact (the subtraction of two nearby floats is
// exact).
// Planes keep their normal and move their offset: D' = D + N·c; instances move their
// translation.
void recenter_on_camera(Scene& scene);

// An interval of light ranges, lo <= hi: each light's drawn uniformly in it.
struct RangeInterval {
  float lo = 1.0f, hi = 1.0f;
};

// Extra lights for `--lights N`: the scene's own lights first, then `total - existing`
// lights: the next lights of the scene's light field if it has one, else lights placed
// deterministically on a ring above the scene's bounds (see scene.cpp). `range`, when
// given, is where the ranges of the extra lights and of the field's own lights are drawn
// from (else the field's, or none for the ring).
void set_light_count(Scene& scene, std::size_t total, std::optional<RangeInterval> range = {});

}  // namespace rt2
