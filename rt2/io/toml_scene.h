// rt2/io/toml_scene.h — a TOML scene file into a Scene (internal).
//
// Part of the implementation of rt2/io/scene_io.h, not an API: rt2::load_scene and
// rt2::load_toml_scene call read_toml_scene through their `guarded` wrapper, which makes
// sure that only rt2::Error, with a one-line message, leaves them. The format is documented
// in scenes/FORMAT.md.
#pragma once

#include <string>

#include "rt2/scene/scene.h"

namespace rt2::io {

// Reads the TOML scene file `path`: screened (size, encoding, key depth, and the invalid
// TOML that toml++ 3.3 mishandles: see TomlScreen in toml_scene.cpp), parsed by toml++,
// walked section by section with Reader; the meshes it names are loaded relative to its
// folder (rt2/io/obj_mesh.h), and the result has passed Scene::validate(). Throws
// rt2::Error naming the file, line and column and key path of the problem.
Scene read_toml_scene(const std::string& path, const AssetPolicy& policy);

// Reads a TOML file that holds only a `[camera]` table, as a scene file's (what the
// interactive viewer prints): the camera that table describes.
Camera read_toml_camera(const std::string& path);

}  // namespace rt2::io
