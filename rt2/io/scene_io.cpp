// rt2/io/scene_io.cpp — the public entry points of rt2/io/scene_io.h: TOML scene files, OBJ/MTL
// meshes and glTF 2.0 files into rt2::Scene.
//
// The work is done in rt2/io/: toml_scene (screening, parsing and the scene sections, on
// top of the typed toml_reader), obj_mesh (OBJ checks, MTL libraries, assembly into a Mesh,
// with the MTL mapping in mtl), gltf_scene (glTF 2.0 through tinygltf), framing (the camera
// and light of a file that has none) and text (the shared message and file helpers). Here each
// entry point runs its loader through `guarded`, so that only rt2::Error, with a one-line
// message, escapes; frame_obj builds the camera, light and ground around a bare OBJ, and
// load_obj leaves the scene as it was on an error.
#include "rt2/io/scene_io.h"

#include <algorithm>
#include <cctype>
#include <exception>
#include <filesystem>
#include <memory>
#include <new>
#include <string>

#include "rt2/base/error.h"
#include "rt2/io/framing.h"
#include "rt2/io/gltf_scene.h"
#include "rt2/io/obj_mesh.h"
#include "rt2/io/text.h"
#include "rt2/io/toml_scene.h"

namespace rt2 {
namespace {

namespace fs = std::filesystem;

using io::error_at;
using io::frame_camera;
using io::Framing;
using io::framing_light;
using io::framing_of;
using io::kMaxObjBytes;
using io::obj_to_mesh;
using io::one_line;
using io::parse_gltf;
using io::ParsedGltf;
using io::read_gltf_scene;
using io::read_text_file;
using io::read_toml_scene;
using io::validate;
using io::WarningsOff;

// How far under a bare OBJ its ground plane is, in units of R (half the mesh's diagonal).
constexpr float kGroundGap = 1e-3f;

// Runs a loader so that only rt2::Error leaves it, always with a one-line message.
template <class F>
auto guarded(const std::string& path, F&& load) -> decltype(load()) {
  try {
    return load();
  } catch (const Error& e) {
    throw Error(one_line(e.what()));
  } catch (const std::bad_alloc&) {
    throw Error(one_line(path + ": out of memory"));
  } catch (const std::exception& e) {
    throw Error(one_line(path + ": " + e.what()));
  } catch (...) {
    throw Error(one_line(path + ": unexpected error"));
  }
}

}  // namespace

Scene load_scene(const std::string& path, const AssetPolicy& policy, const ScenePose& pose) {
  return load_scene(path, policy, pose, nullptr);
}

Scene load_scene(const std::string& path, const AssetPolicy& policy, const ScenePose& pose,
                 ScenePoser* poser) {
  if (poser) *poser = ScenePoser();
  return guarded(path, [&] {
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext == ".gltf" || ext == ".glb") {
      if (!poser) return read_gltf_scene(path, policy, pose);
      std::shared_ptr<ParsedGltf> file = parse_gltf(path, policy);
      Scene scene = read_gltf_scene(*file, path, policy, pose);
      if (scene.animation >= 0) {
        poser->path_ = path;
        poser->policy_ = policy;
        poser->animation_ = pose.animation;
        poser->file_ = std::move(file);
      }
      return scene;
    }
    if ((ext == ".toml" || ext == ".obj") && !pose.animation.empty())
      error_at(path, 0, 0, "has no animations (asked for '" + one_line(pose.animation) + "')");
    if (ext == ".toml") return load_toml_scene(path, policy);
    if (ext == ".obj") return frame_obj(path, policy);
    error_at(path, 0, 0,
             (ext.empty() ? "no file extension" : "unknown file extension '" + ext + "'") +
                 "; expected a .toml scene, an .obj mesh or a .gltf/.glb glTF 2.0 scene");
  });
}

Scene ScenePoser::at(double seconds) const {
  if (!file_) throw Error("ScenePoser::at: no scene to pose");
  const WarningsOff quiet;
  return guarded(path_, [&] {
    return read_gltf_scene(*file_, path_, policy_, ScenePose{animation_, seconds});
  });
}

Scene load_toml_scene(const std::string& path, const AssetPolicy& policy) {
  return guarded(path, [&] { return read_toml_scene(path, policy); });
}

Camera load_camera(const std::string& path) {
  return guarded(path, [&] { return io::read_toml_camera(path); });
}

Scene load_gltf_scene(const std::string& path, const AssetPolicy& policy, const ScenePose& pose) {
  return guarded(path, [&] { return read_gltf_scene(path, policy, pose); });
}

Scene frame_obj(const std::string& obj_path, const AssetPolicy& policy) {
  return guarded(obj_path, [&] {
    Scene scene;
    scene.assets = policy;
    scene.meshes.push_back(load_obj(obj_path, scene));
    const Aabb box = scene.meshes.back().bounds();
    const Framing frame = framing_of(obj_path, box, "mesh");
    const float r = frame.radius;
    frame_camera(scene, frame);
    scene.lights.push_back(framing_light(frame));
    Material ground;
    ground.diffuse = vec4(0.8f, 0.8f, 0.8f);
    ground.diffuse2 = vec4(0.3f, 0.3f, 0.3f);
    ground.checker_scale = r / 4.0f;
    // The ground sits a thousandth of R under the mesh: at the mesh's lowest y exactly, it
    // would z-fight with a mesh's own floor and hide a flat mesh lying on it.
    Plane floor;
    floor.n = vec4(0.0f, 1.0f, 0.0f);
    floor.d = -(box.lo[1] - kGroundGap * r);  // y = lo.y - R / 1000
    scene.planes.push_back(floor);
    scene.plane_materials.push_back(scene.add_material("ground", ground));
    scene.ambient = vec4(0.15f, 0.15f, 0.15f);
    scene.background = vec4(0.05f, 0.05f, 0.08f);
    validate(obj_path, scene);
    return scene;
  });
}

Mesh load_obj(const std::string& path, Scene& scene, int override_material) {
  const std::size_t materials = scene.materials.size();
  const std::size_t degenerate = scene.degenerate_triangles;
  try {
    return guarded(path, [&] {
      return obj_to_mesh(path, read_text_file(path, kMaxObjBytes, ""), scene, override_material);
    });
  } catch (const Error&) {  // leave the scene as it was
    scene.materials.resize(materials);
    scene.material_names.resize(materials);
    scene.degenerate_triangles = degenerate;
    throw;
  }
}

}  // namespace rt2
