// rt2/io/gltf_document.h — a glTF file before tinygltf reads it (internal): the GLB
// container taken apart, the JSON's nesting and size bounded, the schema rt2 relies on
// checked (an error names the JSON path: "materials[0].emissiveFactor has 4 numbers,
// expected 3"), glTF 1.0 and unknown required extensions refused by name, and the JSON
// rewritten where rt2 decodes an extension itself (Draco, meshopt), so that tinygltf reads
// what it can and leaves the rest to rt2/io/gltf_compression.h.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace rt2::io {

// Beyond these a JSON text is an attack, not a scene: tinygltf walks it recursively.
constexpr int kMaxJsonDepth = 128;                 // nested arrays and objects
constexpr std::size_t kMaxJsonValues = 1u << 24;   // values of any kind

// The extensions rt2 reads; any other name in extensionsRequired is refused.
inline constexpr const char* kGltfExtensions[] = {
    "KHR_draco_mesh_compression", "EXT_meshopt_compression", "KHR_mesh_quantization",
    "KHR_texture_transform", "KHR_materials_pbrSpecularGlossiness",
    "KHR_materials_emissive_strength", "KHR_materials_ior", "KHR_materials_transmission",
    "KHR_lights_punctual"};

// A primitive whose geometry is Draco-compressed: its indices accessor, which tinygltf
// cannot read (it has no bufferView) and which the rewritten JSON leaves out, and the
// extension's buffer view and attribute ids.
struct DracoPrimitive {
  int mesh = 0, primitive = 0;
  int indices = -1;  // the accessor, -1 without one
  int view = -1;
  std::vector<std::pair<std::string, std::uint32_t>> attributes;  // glTF name, Draco id
};

// A buffer view whose bytes are EXT_meshopt_compression's decoding of a range of another
// buffer, as the JSON gives it (tinygltf keeps extension numbers as 32-bit ints).
struct MeshoptView {
  int view = 0, buffer = 0;
  std::uint64_t offset = 0, length = 0, stride = 0, count = 0;
  std::string mode, filter = "NONE";
};

struct GltfDocument {
  bool glb = false;
  std::string json;  // as tinygltf is to read it (rewritten where needed)
  std::string bin;   // a GLB's BIN chunk, or empty
  std::vector<DracoPrimitive> draco;
  std::vector<MeshoptView> meshopt;
  // Buffers that EXT_meshopt_compression marks as fallback and that have no data: the
  // rewritten JSON gives them none; only decoded buffer views may point into them.
  std::vector<int> fallback_buffers;
  // Each buffer's uri when it names a file (not a data: URI), else "".
  std::vector<std::string> buffer_files;
  // Whether extensionsUsed names KHR_mesh_quantization (integer texture coordinates may
  // then be unnormalized).
  bool quantized = false;
};

// Checks and takes apart the bytes of `path` (a .gltf's JSON or a .glb), warning once for
// each extension it uses that rt2 ignores. Throws rt2::Error "path: ..." on any problem.
GltfDocument read_gltf_document(const std::string& path, const std::string& bytes);

// The document as the bytes tinygltf loads: the JSON, or a GLB rebuilt around it.
std::string tinygltf_bytes(const GltfDocument& doc);

}  // namespace rt2::io
