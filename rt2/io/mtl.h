// rt2/io/mtl.h — MTL material libraries, read by rt2 and mapped to Materials (internal).
//
// Part of the implementation of rt2/io/scene_io.h, not an API. rt2 reads MTL text itself, not
// through tinyobjloader, which reads `Kd 0.5` as dark red (0.5, 0, 0), turns `Kd red` or
// `Ns nan` into numbers without a word, and keeps some 2 KB of texture fields per material
// (gigabytes for a file of a million materials). read_mtl checks every statement rt2 knows, an
// error naming the MTL file and line, keeps only the materials the OBJ asks for, and warns
// once per file about what rt2 ignores (textures); from_mtl maps a material to a Material as
// scenes/FORMAT.md documents.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>

#include "rt2/scene/material.h"

namespace rt2::io {

// A texture statement of an MTL material: its file name as written (relative to the MTL
// file's folder; rt2/io/obj_mesh.cpp resolves it) and where it is.
struct MtlTexture {
  std::string file;      // empty: none
  std::size_t line = 0;  // the statement's line in the MTL file
};

// One MTL material as written: colours as r g b (one number is grey), the rest as given. The
// defaults are tinyobjloader's, so that a file reads as it would through tinyobjloader.
struct MtlMaterial {
  std::string file;                  // the MTL file, for messages
  float ka[3] = {0.0f, 0.0f, 0.0f};  // Ka
  float kd[3] = {0.0f, 0.0f, 0.0f};  // Kd
  float ks[3] = {0.0f, 0.0f, 0.0f};  // Ks
  bool has_kd = false;
  bool diffuse_texture = false;  // map_Kd: without Kd, the diffuse colour is 0.6 grey
  float ns = 1.0f;               // Ns
  float ni = 1.0f;               // Ni
  bool has_ni = false;
  float d = 1.0f;  // d
  bool has_d = false;
  float tr = 0.0f;  // Tr
  bool has_tr = false;
  int illum = 0;
  float kr = 0.0f;  // Kr (an rt2 extension): the largest of its numbers
  bool has_kr = false;
  // The PBR extension (Exocortex / Blender's exporter): roughness, metallic, emission.
  float pr = 1.0f, pm = 0.0f;  // Pr, Pm
  bool has_pr = false, has_pm = false;
  float ke[3] = {0.0f, 0.0f, 0.0f};  // Ke
  // Texture statements (options such as -bm are read where they matter: norm's -bm is the
  // normal map's scale).
  MtlTexture map_kd, map_ke, map_pr, map_pm, norm;
  float norm_scale = 1.0f;
  bool is_pbr() const { return has_pr || has_pm || !map_pr.file.empty() || !map_pm.file.empty(); }
};

// The materials an OBJ asks for by name (its `usemtl` names), each empty until an MTL library
// defines it.
using MtlMaterials = std::map<std::string, std::optional<MtlMaterial>, std::less<>>;

// Reads the MTL `text` of `file`. Every statement rt2 knows is checked: colours (Ka, Kd, Ks,
// Ke, Kt, Tf, and Kr) take 1 number (grey) or 3, Ns, Ni, d (also `d -halo x`), Tr,
// sharpness and the PBR numbers take one, each finite and within float range, illum an
// integer from 0 to 10; a problem throws rt2::Error "file:LINE: material 'x': Kd must be a
// number (got 'red')". `newmtl NAME` takes the rest of the line as the name (blanks trimmed).
// A material named in `wanted` that has no definition yet gets this one (the first definition
// wins); the others are checked and dropped. Prints one warning for the file if a material
// it keeps has a texture rt2 does not use (bump, refl, map_Ks, ...; map_Kd, map_Ke, map_Pr,
// map_Pm and norm are kept) and one if it has a spectral or CIE XYZ colour (ignored).
void read_mtl(const std::string& file, std::string_view text, MtlMaterials& wanted);

// The mapping documented in scenes/FORMAT.md: a Phong material, or a physically based one
// when the material has any of Pr, Pm, map_Pr, map_Pm. `texture(key, statement, srgb)` adds
// the texture file of the statement `key` ("map_Kd", ...) to the scene and returns its index
// (or kNoTexture to drop it); without it, textures are dropped.
using AddTexture =
    std::function<std::uint32_t(std::string_view key, const MtlTexture& texture, bool srgb)>;
Material from_mtl(const MtlMaterial& t, const AddTexture& texture = nullptr);

}  // namespace rt2::io
