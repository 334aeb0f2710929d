// rt2/io/gltf_scene.h — a glTF 2.0 file (.gltf or .glb) into a Scene (internal).
//
// Part of the implementation of rt2/io/scene_io.h, not an API: rt2::load_scene and
// rt2::load_gltf_scene call read_gltf_scene through their `guarded` wrapper, which makes
// sure that only rt2::Error, with a one-line message, leaves them. tinygltf parses the JSON
// and the buffers; everything rt2 takes from the parsed model (accessors, node graph,
// materials, cameras, KHR_lights_punctual) is checked here before use. What is read and how
// it maps is documented in scenes/FORMAT.md.
#pragma once

#include <memory>
#include <string>

#include "rt2/scene/scene.h"

namespace rt2::io {

// Limits beyond which input is a mistake, not a scene.
constexpr std::size_t kMaxGltfBytes = 2047ull << 20;  // a .gltf, .glb or buffer file
constexpr int kMaxGltfDepth = 1024;                   // node hierarchy depth
constexpr std::size_t kMaxGltfNodeVisits = 1u << 18;  // node instances (a DAG can repeat)
constexpr std::size_t kMaxGltfPrimitives = 1u << 16;  // primitive instances (one Mesh each)
constexpr std::size_t kMaxGltfVertices = 1u << 26;    // all mesh instances together
constexpr std::size_t kMaxGltfLights = 4096;          // light instances (none has a range)
constexpr std::size_t kMaxGltfKeyValues = 1u << 26;   // keyframe numbers of all animations
constexpr std::size_t kMaxGltfMorphTargets = 1024;    // morph targets of a mesh
constexpr std::size_t kMaxGltfMorphReads = 1u << 27;  // target vertices read, all instances
constexpr std::size_t kMaxGltfJoints = 1u << 16;      // joints of a skin (JOINTS_0 is 16-bit)

// Reads the glTF 2.0 file `path` (JSON or binary, told apart by its first bytes, "glTF"
// for binary). Images are not decoded: a file image becomes a TextureDesc with its path
// (relative to the glTF's folder, checked to be a regular file), an embedded one its bytes.
// The default scene's nodes are walked with their transforms; primitives become meshes,
// materials PBR materials, the first camera the scene's camera, KHR_lights_punctual lights
// point lights; without a camera or lights the scene is framed as a bare OBJ is. The result
// has passed Scene::validate(). Throws rt2::Error "path: ..." naming the element at fault.
//
// The nodes are posed as animation `pose.animation` (by name or index; the first when empty)
// moves them at `pose.seconds`; every animation is checked, and listed in Scene::animations.
// A skinned mesh's vertices are placed by its skin's joints as posed (glTF 2.0 3.7.3).
Scene read_gltf_scene(const std::string& path, const AssetPolicy& policy,
                      const ScenePose& pose = {});

// A glTF file parsed once and read at many poses: parse_gltf reads and parses `path` (the
// file and its buffers; throws as read_gltf_scene does), and read_gltf_scene(file, ...)
// returns what read_gltf_scene(path, ...) would, bit for bit, without reading or parsing
// the file and its buffers again (image files are only checked to exist; the first reading
// also keeps the checked animations and the still framing).
struct ParsedGltf;
std::shared_ptr<ParsedGltf> parse_gltf(const std::string& path, const AssetPolicy& policy);
Scene read_gltf_scene(ParsedGltf& file, const std::string& path, const AssetPolicy& policy,
                      const ScenePose& pose);

}  // namespace rt2::io
