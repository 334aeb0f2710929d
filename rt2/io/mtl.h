// rt2/io/mtl.h — MTL materials into rt2 Materials (internal).
//
// Part of the implementation of rt2/scene_io.h, not an API. tinyobjloader parses the MTL
// libraries; from_mtl maps each of its materials to a Material as scenes/FORMAT.md
// documents (colours, shininess, Ni, d/Tr, illum, and the rt2 extension Kr). scan_mtl reads
// the MTL text for what tinyobjloader does not report (whether Ni was given, the line of a
// Kr), so that a bad Kr can be reported at its line; normalize_mtl makes the material names
// that tinyobjloader sees agree with those scan_mtl and `usemtl` use.
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

// The name of the material that the MTL line `line` (blanks trimmed at both ends, as
// for_each_line gives it) starts, or "" when it is not a `newmtl` line. Blanks between
// `newmtl` and the name are not part of it; blanks inside it are ("newmtl  my red" names
// "my red"). tinyobjloader keeps all but the first blank ("newmtl  red" is " red" to it), so
// that `usemtl red`, whose name it reads as one token, would not find the material:
// normalize_mtl rewrites the text that tinyobjloader sees to agree with this name.
std::string_view newmtl_name(std::string_view line);

// The MTL `text` with each line as for_each_line gives it (blanks trimmed, "\n" endings) and
// each `newmtl` line rewritten as "newmtl " + newmtl_name: what rt2 gives tinyobjloader, so
// that its material names are those of scan_mtl.
std::string normalize_mtl(std::string_view text);

// Collects the MtlFacts of each `newmtl` in the MTL `text` of `file` into `facts` (by
// material name as newmtl_name reads it; a later material of the same name starts afresh).
void scan_mtl(const std::string& file, std::string_view text,
              std::map<std::string, MtlFacts>& facts);

// The mapping documented in scenes/FORMAT.md.
Material from_mtl(const tinyobj::material_t& t, const MtlFacts& facts);

}  // namespace rt2::io
