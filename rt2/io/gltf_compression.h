// rt2/io/gltf_compression.h — what tinygltf leaves encoded, decoded into its model
// (internal): EXT_meshopt_compression buffer views (Debian's libmeshoptimizer) and
// KHR_draco_mesh_compression primitives (Debian's libdraco). Afterwards every accessor the
// scene reads is a plain view of a buffer, as in an uncompressed file.
#pragma once

#include <string>

#include "rt2/io/gltf_document.h"

namespace tinygltf {
class Model;
}

namespace rt2::io {

// The most bytes decoding may produce in all, on top of the file's own.
constexpr std::size_t kMaxDecodedBytes = std::size_t(4) << 30;

// Decodes every meshopt buffer view and Draco primitive of `model` (read from `doc`) into
// new buffers, and points the buffer views, accessors and primitives at them. Throws
// rt2::Error "path: ..." naming the element for malformed or oversized data.
void decode_compressed(const std::string& path, const GltfDocument& doc, tinygltf::Model& model);

}  // namespace rt2::io
