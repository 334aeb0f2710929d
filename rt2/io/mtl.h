// rt2/io/mtl.h — MTL materials into rt2 Materials (internal).
//
// Part of the implementation of rt2/scene_io.h, not an API. tinyobjloader parses the MTL
// libraries; from_mtl maps each of its materials to a Material as scenes/FORMAT.md
// documents (colours, shininess, Ni, d/Tr, illum, and the rt2 extension Kr). scan_mtl reads
// the MTL text for what tinyobjloader does not report (whether Ni was given, the line of a
// Kr), so that a bad Kr can be reported at its line.
#pragma once

#include <tiny_obj_loader.h>

#include <cstddef>
#include <map>
#include <string>
#include <string_view>

#include "rt2/material.h"

namespace rt2::io {

// What tinyobjloader does not tell about an MTL material: where it is, whether Ni was given
// (it reports a missing Ni as 1) and the line of a Kr.
struct MtlFacts {
  std::string file;
  bool has_ni = false;
  std::size_t kr_line = 0;
};

// Collects the MtlFacts of each `newmtl` in the MTL `text` of `file` into `facts` (by
// material name; a later material of the same name starts afresh).
void scan_mtl(const std::string& file, std::string_view text,
              std::map<std::string, MtlFacts>& facts);

// The mapping documented in scenes/FORMAT.md.
Material from_mtl(const tinyobj::material_t& t, const MtlFacts& facts);

}  // namespace rt2::io
