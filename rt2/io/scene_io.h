// rt2/io/scene_io.h — loading scenes: TOML scene files (toml++), OBJ/MTL meshes
// (tinyobjloader) and glTF 2.0 scenes (.gltf, .glb; tinygltf). The scene format and the
// MTL → Material mapping are documented in scenes/FORMAT.md.
//
// Every problem in the input — a missing file, a syntax error, an unknown key, a value out
// of range, a bad face index — throws rt2::Error with a one-line message that starts with
// the file and, where there is one, the line and column:
//   scenes/x.toml:12:10: spheres[1].radius must be > 0 (got -1)
// No other exception escapes, and the loaded scene has passed Scene::validate(). Non-fatal
// problems (a missing MTL library) are printed to stderr as one `warning: ...` line each.
#pragma once

#include <memory>
#include <string>

#include "rt2/base/error.h"
#include "rt2/scene/mesh.h"
#include "rt2/scene/scene.h"

namespace rt2 {

// Loads `path` by its extension (any case): a .toml scene file, a bare .obj mesh which is
// framed automatically, or a .gltf/.glb glTF 2.0 scene, under `policy` (which the scene
// keeps, Scene::assets), posed as `pose` says (a glTF's animation at a time; a scene of
// another format has none, and naming one is an error). Throws rt2::Error with a one-line
// message on any problem.
Scene load_scene(const std::string& path, const AssetPolicy& policy = {},
                 const ScenePose& pose = {});

namespace io {
struct ParsedGltf;
}

// A scene that moves, kept as its file was parsed: at(seconds) returns
// load_scene(path, policy, {animation, seconds}) bit for bit without reading or parsing the
// file and its buffers again, so that a frame costs the walk of the nodes, skinning and
// morphing, not the file. Empty (`!poser`) for a scene without animations.
class ScenePoser {
 public:
  ScenePoser() = default;
  explicit operator bool() const { return file_ != nullptr; }
  // Throws rt2::Error as load_scene does; prints no warnings (the first load printed them).
  Scene at(double seconds) const;

 private:
  friend Scene load_scene(const std::string&, const AssetPolicy&, const ScenePose&, ScenePoser*);
  std::string path_;
  AssetPolicy policy_;
  std::string animation_;
  std::shared_ptr<io::ParsedGltf> file_;
};

// load_scene, and for an animated scene a poser of it in `*poser` (else an empty one).
Scene load_scene(const std::string& path, const AssetPolicy& policy, const ScenePose& pose,
                 ScenePoser* poser);

// Loads a TOML scene file (scenes/FORMAT.md). Mesh paths are relative to its folder.
Scene load_toml_scene(const std::string& path, const AssetPolicy& policy = {});

// Reads a TOML file holding only a `[camera]` table (scenes/FORMAT.md; the block the
// interactive viewer prints with `C`): the camera it describes.
Camera load_camera(const std::string& path);

// Loads a glTF 2.0 scene, JSON (.gltf) or binary (.glb), told apart by its content
// (scenes/FORMAT.md: what is read and how it maps). Without a camera or without lights it is
// framed as frame_obj frames an OBJ (no ground plane). Buffer and image files are relative
// to its folder; images are not decoded here (TextureDesc). The nodes are posed as
// animation `pose.animation` (name or index, "" the first) moves them at `pose.seconds`;
// Scene::animations lists the file's animations.
Scene load_gltf_scene(const std::string& path, const AssetPolicy& policy = {},
                      const ScenePose& pose = {});

// A bare OBJ, framed (rt2/io/framing.h): a camera looking at its bounding box from above,
// in front and to the right, the whole box in view (Scene::framed_bounds records the box, so
// that the camera can be fitted to the image), one white light above the camera's side, a
// ground plane with a checker material just under the box (R / 1000 below it, R half the
// box's diagonal), MTL materials or a default grey material.
Scene frame_obj(const std::string& obj_path, const AssetPolicy& policy = {});

// A framed scene (a bare OBJ, a glTF without a camera: Scene::framed_bounds) gets the camera
// that shows its whole bounding sphere in a width x height image (both > 0); any other
// scene is left as it is.
void fit_framed_camera(Scene& scene, int width, int height);

// Reads an OBJ (and its MTL libraries) through tinyobjloader into a Mesh. Each face's material
// is `override_material` when >= 0, else the MTL material (added to `scene`; name
// "<objfile>:<mtlname>"), else a default material (added once, name "default"). Degenerate
// faces (zero/non-finite area) are dropped and added to scene.degenerate_triangles. Positions
// and normals get w = 0. The files it names are read under scene.assets. On an error `scene`
// is left as it was.
Mesh load_obj(const std::string& path, Scene& scene, int override_material = -1);

}  // namespace rt2
