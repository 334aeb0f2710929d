// rt2/io/obj_mesh.h — an OBJ file (and its MTL libraries) into a Mesh (internal).
//
// Part of the implementation of rt2/io/scene_io.h, not an API: used by rt2::load_obj and
// rt2::frame_obj (rt2/io/scene_io.cpp) and by the [[meshes]] of a TOML scene
// (rt2/io/toml_scene.cpp). The caller reads the OBJ text (read_text_file, at most
// kMaxObjBytes), so that a missing file is reported in the caller's terms.
#pragma once

#include <cstddef>
#include <string>

#include "rt2/scene/mesh.h"
#include "rt2/scene/scene.h"

namespace rt2::io {

// Limits beyond which input is a mistake, not a scene.
constexpr std::size_t kMaxObjBytes = 4096ull << 20;  // an OBJ or MTL file

// The Mesh of the OBJ `text`, read from `path` (a UTF-8 byte-order mark, in it or in an MTL
// library, is skipped): the text is checked first (every problem named with its line), its
// MTL libraries are read relative to `path` (a missing one is a warning; none is read when
// `override_material` >= 0), tinyobjloader parses the OBJ, and polygons are triangulated
// (a warning names the first that ear clipping gave up on). Names written on Windows
// (backslashes, drives) are read as scenes/FORMAT.md says; unless
// scene.assets.allow_outside_assets, MTL libraries and textures must lie in the OBJ's folder
// after `..` and symbolic links, or this throws "file:line: mtllib '../x.mtl' lies outside
// the asset's folder (--allow-outside-assets reads it)". Face materials and degenerate
// faces are as rt2::load_obj documents (rt2/io/scene_io.h), but on an error `scene` may keep
// materials already added: restoring it is the caller's job. Throws rt2::Error.
Mesh obj_to_mesh(const std::string& path, const std::string& text, Scene& scene,
                 int override_material);

// Why every face of `mesh` was dropped as degenerate, as the end of a message: " (zero or
// non-finite area)", or that the coordinates are too large or too small for a float area
// (`range`: area_out_of_range of the mesh before its faces were dropped).
std::string degenerate_reason(const Mesh& mesh, const AreaOutOfRange& range);

}  // namespace rt2::io
