// rt2/io/obj_mesh.cpp — OBJ text and its MTL libraries into a Mesh (internal; see
// rt2/io/obj_mesh.h).
//
// tinyobjloader parses the OBJ but accepts bad input silently (an unparsable coordinate
// becomes 0, an out-of-range index is a warning or a skipped face), so the OBJ text is
// scanned first to report such problems with their line numbers, and to note what
// tinyobjloader drops or keeps wrongly: each face's material (`usemtl` takes the rest of the
// line) and the corner count of faces of 256 corners or more (stored in a byte). MTL
// libraries (relative to the OBJ, rt2/io/mtl.h) give the materials the faces name; polygons
// are split by rt2/io/polygon_triangulation.h; the faces become a Mesh.
#include "rt2/io/obj_mesh.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cfloat>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <utility>
#include <vector>

#include "rt2/base/error.h"
#include "rt2/io/asset_path.h"
#include "rt2/io/mtl.h"
#include "rt2/io/polygon_triangulation.h"
#include "rt2/io/text.h"

namespace rt2::io {
namespace {

namespace fs = std::filesystem;

// ---- OBJ scanning -----------------------------------------------------------------------

bool parse_index(std::string_view token, long long& v) {
  if (token.starts_with('+')) token.remove_prefix(1);  // atoi, as tinyobjloader, accepts it
  const auto r = std::from_chars(token.data(), token.data() + token.size(), v);
  return !token.empty() && r.ec == std::errc() && r.ptr == token.data() + token.size();
}

// What an OBJ file says, as far as the checks and the assembly need it.
struct ObjScan {
  std::size_t faces = 0;
  std::vector<std::pair<std::string, std::size_t>> libraries;  // mtllib names and lines, in order
  // Faces of 256 corners or more: (face number from 0, corners).
  std::vector<std::pair<std::size_t, std::size_t>> big_faces;
  // The usemtl names in the order of their first use, with that line; and from face `first`
  // on, the faces use name number `second`.
  std::vector<std::string> material_names;
  std::vector<std::size_t> material_lines;
  std::vector<std::pair<std::size_t, std::uint32_t>> material_runs;
};

struct IndexKind {
  const char* one;
  const char* many;
};
constexpr IndexKind kVertexKind{"vertex", "vertices"};
constexpr IndexKind kTexcoordKind{"texture coordinate", "texture coordinates"};
constexpr IndexKind kNormalKind{"normal", "normals"};

// An OBJ index: 1..total, or relative -1..-defined (defined: how many come before the face).
void check_index(const std::string& file, std::size_t line, long long idx, std::size_t defined,
                 std::size_t total, const IndexKind& kind) {
  const std::string k = kind.one;
  if (idx == 0) error_at(file, line, 0, "face references " + k + " 0, but OBJ indices start at 1");
  if (idx > 0 && static_cast<unsigned long long>(idx) > total) {
    error_at(file, line, 0,
             "face references " + k + " " + std::to_string(idx) + ", but only " +
                 std::to_string(total) + " " + (total == 1 ? k : kind.many) + " " +
                 (total == 1 ? "is" : "are") + " defined");
  }
  if (idx < 0 && (idx == LLONG_MIN || static_cast<unsigned long long>(-idx) > defined)) {
    error_at(file, line, 0,
             "face references " + k + " " + std::to_string(idx) + " (relative), but only " +
                 std::to_string(defined) + " " + (defined == 1 ? k : kind.many) +
                 " are defined before it");
  }
}

// "v x y z": three finite coordinates that fit a float.
void check_vertex(const std::string& file, std::size_t line,
                  const std::vector<std::string_view>& t) {
  if (t.size() < 4)
    error_at(file, line, 0, "vertex needs 3 coordinates, got " + std::to_string(t.size() - 1));
  for (std::size_t i = 1; i <= 3; ++i) {
    double v = 0.0;
    if (!parse_double(t[i], v))
      error_at(file, line, 0, "vertex coordinate '" + std::string(t[i]) + "' is not a number");
    if (!std::isfinite(v) || std::fabs(v) > FLT_MAX)
      error_at(file, line, 0, "vertex is not finite (coordinate '" + std::string(t[i]) + "')");
  }
}

// "f a b c ...", each corner v, v/vt, v//vn or v/vt/vn.
void check_face(const std::string& file, std::size_t line, const std::vector<std::string_view>& t,
                const std::size_t defined[3], const std::size_t total[3]) {
  if (t.size() < 4)
    error_at(file, line, 0,
             "face has " + std::to_string(t.size() - 1) + " vertices; at least 3 are needed");
  const IndexKind* kinds[3] = {&kVertexKind, &kTexcoordKind, &kNormalKind};
  for (std::size_t c = 1; c < t.size(); ++c) {
    std::string_view rest = t[c];
    for (std::size_t part = 0; part < 3 && !rest.empty(); ++part) {
      const std::size_t slash = std::min(rest.find('/'), rest.size());
      const std::string_view number = rest.substr(0, slash);
      rest = slash < rest.size() ? rest.substr(slash + 1) : std::string_view();
      if (number.empty() && part > 0) continue;  // v//vn, or a trailing slash
      long long idx = 0;
      if (!parse_index(number, idx))
        error_at(file, line, 0, "face corner '" + std::string(t[c]) + "' is not an index");
      check_index(file, line, idx, defined[part], total[part], *kinds[part]);
    }
    if (!rest.empty())
      error_at(file, line, 0, "face corner '" + std::string(t[c]) + "' has more than 3 parts");
  }
}

// Refuses a value of the statement `t` (its tokens after the keyword) that tinyobjloader
// would parse as a real and overflow on (see huge_exponent).
void check_reals(const std::string& file, std::size_t line,
                 const std::vector<std::string_view>& t) {
  check_exponents(file, line, std::span(t).subspan(1));
}

// The number that atoi, as tinyobjloader uses it, reads at the start of `s` (0 if none),
// saturated instead of overflowing.
long long atoi_prefix(std::string_view s) {
  std::size_t i = s.starts_with('+') || s.starts_with('-') ? 1 : 0;
  long long n = 0;
  for (; i < s.size() && s[i] >= '0' && s[i] <= '9'; ++i)
    n = std::min(n * 10 + (s[i] - '0'), 1LL << 40);
  return s.starts_with('-') ? -n : n;
}

// "t name ints/reals/strings values...": tinyobjloader allocates and parses as many values as
// the counts say (up to 8192 each, even when the line has none), so a short line could cost
// hundreds of kilobytes; the line `s` must hold the values it declares. The counts are read
// as tinyobjloader's parseTagTriple reads them: blanks are skipped before each count, also
// after a '/' ("0/ 8192/ 8192" declares 16 384 values).
void check_tag(const std::string& file, std::size_t line, std::string_view s) {
  const auto skip = [&s](std::size_t n) { s.remove_prefix(std::min(n, s.size())); };
  const auto skip_blanks = [&] { skip(s.find_first_not_of(" \t")); };
  skip(1);  // "t"
  skip_blanks();
  skip(s.find_first_of(" \t\r"));  // the name
  long long declared = 0;
  for (int k = 0; k < 3; ++k) {
    skip_blanks();
    declared += std::clamp(atoi_prefix(s), 0LL, 8192LL);
    skip(s.find_first_of(k < 2 ? "/ \t\r" : " \t\r"));
    if (k == 2 || !s.starts_with('/')) break;
    skip(1);
  }
  const std::vector<std::string_view> values = split_blanks(s);
  if (declared > static_cast<long long>(values.size()))
    error_at(file, line, 0,
             "tag declares " + std::to_string(declared) + " values, but the line has " +
                 std::to_string(values.size()));
  check_exponents(file, line, values);
}

// Two passes: the totals of v, vt and vn first (a face may name a vertex defined after it,
// as tinyobjloader allows), then every line.
ObjScan scan_obj(const std::string& file, std::string_view text) {
  std::size_t total[3] = {0, 0, 0};
  for_each_line(text, [&](std::size_t, std::string_view s) {
    const std::string_view head = s.substr(0, std::min(s.find_first_of(" \t"), s.size()));
    total[0] += head == "v";
    total[1] += head == "vt";
    total[2] += head == "vn";
  });
  ObjScan scan;
  std::unordered_map<std::string_view, std::uint32_t> name_numbers;
  std::size_t defined[3] = {0, 0, 0};
  for_each_line(text, [&](std::size_t line, std::string_view s) {
    if (s.empty() || s[0] == '#') return;
    const std::vector<std::string_view> t = split_blanks(s);
    if (t[0] == "v") {
      check_vertex(file, line, t);
      check_reals(file, line, t);
      ++defined[0];
    } else if (t[0] == "vt") {
      check_reals(file, line, t);
      ++defined[1];
    } else if (t[0] == "vn") {
      check_reals(file, line, t);
      ++defined[2];
    } else if (t[0] == "vw") {
      check_reals(file, line, t);
    } else if (t[0] == "t") {
      check_tag(file, line, s);
    } else if (t[0] == "f") {
      check_face(file, line, t, defined, total);
      if (t.size() - 1 >= 256) scan.big_faces.emplace_back(scan.faces, t.size() - 1);
      ++scan.faces;
    } else if (t[0] == "mtllib") {
      for (std::size_t i = 1; i < t.size(); ++i) scan.libraries.emplace_back(t[i], line);
    } else if (t[0] == "usemtl") {
      const std::string_view name = after_keyword(s);  // "usemtl Hard Wood": "Hard Wood"
      const auto [it, added] =
          name_numbers.try_emplace(name, static_cast<std::uint32_t>(scan.material_names.size()));
      if (added) {
        scan.material_names.emplace_back(name);
        scan.material_lines.push_back(line);
      }
      scan.material_runs.emplace_back(scan.faces, it->second);
    }
  });
  return scan;
}

// ---- files an OBJ or MTL names ---------------------------------------------------------

// A file name as an OBJ or MTL written on Windows may give it, as a path here: backslashes
// separate folders (`.\tex.jpg`, `textures\wood.png`); a name on a drive (`C:\tex\wood.png`,
// `C:wood.png`) or rooted by a backslash (`\tex\wood.png`, `\\server\share\wood.png`)
// can name no file here and is taken as its file name alone (`wood.png`).
fs::path portable_path(std::string_view written) {
  std::string s(written);
  const bool drive = s.size() >= 2 && s[1] == ':' &&
                     std::isalpha(static_cast<unsigned char>(s[0]));
  const bool windows_root = drive || s.starts_with('\\');
  std::replace(s.begin(), s.end(), '\\', '/');
  if (windows_root) return fs::path(s.substr(drive ? 2 : 0)).filename();
  return fs::path(s);
}

bool same_ignoring_case(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) ==
                  std::tolower(static_cast<unsigned char>(y));
         });
}

// `path` if it exists; else the path whose missing components are each the one entry of
// their folder that matches them ignoring (ASCII) case, as Windows' file systems match
// names; else (no such entry, or several) `path`.
fs::path find_ignoring_case(const fs::path& path) {
  std::error_code ec;
  if (fs::symlink_status(path, ec).type() != fs::file_type::not_found) return path;
  fs::path at = path.root_path();
  for (const fs::path& part : path.relative_path()) {
    const fs::path next = at / part;
    if (part == "." || part == ".." ||
        fs::symlink_status(next, ec).type() != fs::file_type::not_found) {
      at = next;
      continue;
    }
    fs::path match;
    int matches = 0;
    for (fs::directory_iterator it(at.empty() ? fs::path(".") : at, ec), end;
         !ec && it != end && matches < 2; it.increment(ec)) {
      if (same_ignoring_case(it->path().filename().string(), part.string())) {
        match = it->path().filename();
        ++matches;
      }
    }
    if (matches != 1) return path;
    at /= match;
  }
  return at;
}

// The file an OBJ (mtllib) or an MTL (a texture statement) names: `written`, relative to
// `folder` (the naming file's), as portable_path and find_ignoring_case find it. With a
// `root` (the folder of the OBJ; none when the scene's AssetPolicy allows outside
// assets), a file that is regular or missing must lie in `root`, or this throws
// "`where`: `key` 'written' lies outside the asset's folder (--allow-outside-assets reads it)".
// A device, pipe or folder is the caller's to refuse: it is never read.
fs::path resolve_asset(const fs::path& folder, std::string_view written,
                       const std::optional<fs::path>& root, const std::string& where,
                       std::string_view key) {
  const auto confine = [&](const fs::path& p) {
    if (!root) return;
    std::error_code ec;
    const fs::file_type type = fs::status(p, ec).type();
    if (type != fs::file_type::regular && type != fs::file_type::not_found) return;
    if (!lies_inside(p.string(), root->string()))
      throw Error(one_line(where + ": " + std::string(key) + " '" + std::string(written) +
                           "' lies outside the asset's folder (--allow-outside-assets reads it)"));
  };
  const fs::path as_written = folder / portable_path(written);
  confine(as_written);
  const fs::path found = find_ignoring_case(as_written);
  if (found != as_written) confine(found);
  return found;
}

// The folder an OBJ's MTL libraries and textures must lie in under `policy`; none when it
// allows outside assets.
std::optional<fs::path> asset_root(const std::string& obj_path, const AssetPolicy& policy) {
  if (policy.allow_outside_assets) return std::nullopt;
  const fs::path folder = fs::path(obj_path).parent_path();
  return folder.empty() ? fs::path(".") : folder;
}

// ---- MTL libraries and face materials ---------------------------------------------------

// The scene material of each face of one OBJ: `override_material` if >= 0, else its MTL
// material, else "default". Added on first use, so that MTL entries no face uses and an
// unneeded default do not clutter the scene. Faces are asked for in order.
class FaceMaterials {
 public:
  FaceMaterials(Scene& scene, const std::string& obj_path, const ObjScan& scan,
                const MtlMaterials& mtl, int override_material, std::optional<fs::path> root)
      : scene_(scene),
        obj_path_(obj_path),
        root_(std::move(root)),
        scan_(scan),
        mtl_(mtl),
        ids_(scan.material_names.size(), -1),
        override_(override_material) {}

  std::uint32_t operator()(std::size_t face) {
    if (override_ >= 0) return static_cast<std::uint32_t>(override_);
    const auto& runs = scan_.material_runs;
    while (run_ < runs.size() && runs[run_].first <= face) ++run_;
    if (run_ == 0) return fallback();
    const std::uint32_t name = runs[run_ - 1].second;
    int& id = ids_[name];
    if (id < 0) {
      const std::string& mtl_name = scan_.material_names[name];
      const auto it = mtl_.find(mtl_name);
      id = it == mtl_.end() || !it->second
               ? static_cast<int>(fallback())
               : static_cast<int>(
                     scene_.add_material(fs::path(obj_path_).filename().string() + ":" + mtl_name,
                                         from_mtl(*it->second, add_texture(*it->second))));
    }
    return static_cast<std::uint32_t>(id);
  }

 private:
  // Texture files of MTL material `t`, relative to its MTL file's folder (resolve_asset):
  // added to the scene once per file and colour space; a file that is missing or not a
  // regular file is dropped with a warning (the material keeps its colours, as for a missing
  // MTL library).
  AddTexture add_texture(const MtlMaterial& t) {
    return [this, &t](std::string_view key, const MtlTexture& texture,
                      bool srgb) -> std::uint32_t {
      const std::string where = location(t.file, texture.line, 0);
      const std::string path =
          resolve_asset(fs::path(t.file).parent_path(), texture.file, root_, where, key).string();
      std::error_code ec;
      if (!fs::is_regular_file(path, ec)) {
        warn(where + ": texture '" + texture.file + "' " +
             (fs::exists(path, ec) ? "is not a regular file" : "not found") + "; ignored");
        return kNoTexture;
      }
      for (std::size_t i = 0; i < scene_.textures.size(); ++i)
        if (scene_.textures[i].path == path && scene_.textures[i].srgb == srgb)
          return static_cast<std::uint32_t>(i);
      scene_.textures.push_back(TextureDesc{path, {}, srgb});
      return static_cast<std::uint32_t>(scene_.textures.size() - 1);
    };
  }

  std::uint32_t fallback() {
    if (default_ < 0) {
      const int m = scene_.find_material("default");
      default_ = m >= 0 ? m : static_cast<int>(scene_.add_material("default", Material{}));
    }
    return static_cast<std::uint32_t>(default_);
  }

  Scene& scene_;
  const std::string& obj_path_;
  std::optional<fs::path> root_;  // resolve_asset's
  const ObjScan& scan_;
  const MtlMaterials& mtl_;
  std::vector<int> ids_;  // the scene material of each usemtl name, -1 until used
  int override_;
  int default_ = -1;
  std::size_t run_ = 0;  // material_runs before this one have started
};

// The materials that the usemtl names name, from the MTL libraries that exist (read in the
// order named, found by resolve_asset under `root`), warning about the others. Returns
// whether one was missing.
bool read_libraries(const std::string& obj_path, const ObjScan& scan, MtlMaterials& materials,
                    const std::optional<fs::path>& root) {
  const fs::path folder = fs::path(obj_path).parent_path();
  std::set<std::string> seen;
  bool missing = false;
  for (const auto& [name, line] : scan.libraries) {
    if (!seen.insert(name).second) continue;
    const std::string path =
        resolve_asset(folder, name, root, location(obj_path, line, 0), "mtllib").string();
    std::error_code ec;
    const fs::file_type type = fs::status(path, ec).type();
    if (type != fs::file_type::regular) {  // devices and pipes need not end: not read
      missing = true;
      const std::string why = type == fs::file_type::not_found ? "not found"
                              : ec                             ? "cannot be read: " + ec.message()
                                                               : "is not a regular file";
      warn(obj_path + ": material library '" + name + "' " + why + "; using the default material");
      continue;
    }
    read_mtl(path, without_bom(read_text_file(path, kMaxObjBytes, "")), materials);
  }
  return missing;
}

// Materials for faces that name an MTL material the libraries do not have.
void warn_unknown_usemtl(const std::string& path, const ObjScan& scan, const MtlMaterials& mtl) {
  for (std::size_t i = 0; i < scan.material_names.size(); ++i) {
    const auto it = mtl.find(scan.material_names[i]);
    if (it != mtl.end() && it->second) continue;
    warn(location(path, scan.material_lines[i], 0) + ": material '" + scan.material_names[i] +
         "' is not in the material libraries; using the default material");
  }
}

// ---- OBJ to Mesh ------------------------------------------------------------------------

// Smooth shading needs a usable normal at every corner; otherwise the mesh is flat.
bool usable_normals(const tinyobj::attrib_t& a, const std::vector<tinyobj::shape_t>& shapes) {
  const std::size_t n = a.normals.size() / 3;
  if (n == 0) return false;
  for (const auto& shape : shapes) {
    for (const tinyobj::index_t& ix : shape.mesh.indices) {
      if (ix.normal_index < 0 || static_cast<std::size_t>(ix.normal_index) >= n) return false;
      const float* v = &a.normals[3 * static_cast<std::size_t>(ix.normal_index)];
      const float len2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
      if (!(len2 > 0.0f) || !std::isfinite(len2)) return false;
    }
  }
  return true;
}

// A corner's key: its position, normal + 1 and texture coordinate + 1 (0: none).
struct CornerHash {
  std::size_t operator()(const std::array<std::uint32_t, 3>& k) const {
    std::uint64_t h = (std::uint64_t(k[0]) << 32) ^ (std::uint64_t(k[1]) * 0x9E3779B97F4A7C15ull);
    h ^= std::uint64_t(k[2]) * 0xC2B2AE3D27D4EB4Full;
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

// Texture coordinates need a usable one at every corner; otherwise the mesh has none.
bool usable_texcoords(const tinyobj::attrib_t& a, const std::vector<tinyobj::shape_t>& shapes) {
  const std::size_t n = a.texcoords.size() / 2;
  if (n == 0) return false;
  for (const auto& shape : shapes)
    for (const tinyobj::index_t& ix : shape.mesh.indices) {
      if (ix.texcoord_index < 0 || static_cast<std::size_t>(ix.texcoord_index) >= n) return false;
      const float* t = &a.texcoords[2 * static_cast<std::size_t>(ix.texcoord_index)];
      if (!std::isfinite(t[0]) || !std::isfinite(t[1])) return false;
    }
  return true;
}

// Polygons that ear clipping gave up on (rt2/io/polygon_triangulation.h): how many, and the
// first one's face number and corners.
struct Fallbacks {
  std::size_t count = 0, first_face = 0, first_corners = 0;
};

// Positions (and normals) per distinct corner, faces (polygons triangulated), and a scene
// material per face. tinyobjloader keeps each polygon's corners in order, and its face
// count in a byte: the faces of 256 corners or more take theirs from the scan.
Mesh assemble(const std::string& path, const tinyobj::ObjReader& reader, const ObjScan& scan,
              FaceMaterials& materials, Fallbacks& fallbacks) {
  const tinyobj::attrib_t& a = reader.GetAttrib();
  const std::size_t nv = a.vertices.size() / 3;
  const bool smooth = usable_normals(a, reader.GetShapes());
  const bool textured = usable_texcoords(a, reader.GetShapes());
  Mesh mesh;
  mesh.name = path;
  std::unordered_map<std::array<std::uint32_t, 3>, std::uint32_t, CornerHash> corners;
  auto corner = [&](const tinyobj::index_t& ix) {
    const auto v = static_cast<std::size_t>(ix.vertex_index);
    const int n = smooth ? ix.normal_index : -1;
    const int tc = textured ? ix.texcoord_index : -1;
    const std::array<std::uint32_t, 3> key{static_cast<std::uint32_t>(v), std::uint32_t(n + 1),
                                           std::uint32_t(tc + 1)};
    const auto [it, added] =
        corners.try_emplace(key, static_cast<std::uint32_t>(mesh.positions.size()));
    if (added) {
      mesh.positions.push_back(
          vec4(a.vertices[3 * v], a.vertices[3 * v + 1], a.vertices[3 * v + 2]));
      if (smooth) {
        const float* p = &a.normals[3 * static_cast<std::size_t>(n)];
        mesh.normals.push_back(normalize(vec4(p[0], p[1], p[2])));
      }
      if (textured) {
        const float* t = &a.texcoords[2 * static_cast<std::size_t>(tc)];
        mesh.texcoords.push_back({t[0], t[1]});
      }
    }
    return it->second;
  };
  const auto mismatch = [&] {
    error_at(path, 0, 0, "tinyobjloader returned other faces than the file has");
  };
  PolygonTriangulator triangulator;
  std::vector<vec4> polygon;
  std::vector<CornerTriangle> triangles;
  std::size_t face = 0, big = 0;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const tinyobj::mesh_t& m = shape.mesh;
    std::size_t offset = 0;
    for (const unsigned char byte : m.num_face_vertices) {
      std::size_t count = byte;
      if (big < scan.big_faces.size() && scan.big_faces[big].first == face) {
        count = scan.big_faces[big++].second;
        if (count % 256 != byte) mismatch();
      }
      if (count < 3 || offset + count > m.indices.size()) mismatch();
      const std::span<const tinyobj::index_t> ix(m.indices.data() + offset, count);
      for (const tinyobj::index_t& i : ix)
        if (i.vertex_index < 0 || static_cast<std::size_t>(i.vertex_index) >= nv)
          error_at(path, 0, 0, "tinyobjloader returned a vertex index out of range");
      polygon.clear();
      for (const tinyobj::index_t& i : ix) {
        const float* p = &a.vertices[3 * static_cast<std::size_t>(i.vertex_index)];
        polygon.emplace_back(p[0], p[1], p[2]);
      }
      triangles.clear();
      if (!triangulator.triangulate(polygon, triangles) && fallbacks.count++ == 0) {
        fallbacks.first_face = face;
        fallbacks.first_corners = count;
      }
      const std::uint32_t material = materials(face);
      for (const CornerTriangle& t : triangles) {
        mesh.faces.push_back({corner(ix[t[0]]), corner(ix[t[1]]), corner(ix[t[2]])});
        mesh.face_materials.push_back(material);
      }
      offset += count;
      ++face;
    }
    if (offset != m.indices.size()) mismatch();
  }
  if (face != scan.faces) mismatch();
  return mesh;
}

// The line of face number `face` (from 0) of the OBJ `text`, for a message.
std::size_t face_line(std::string_view text, std::size_t face) {
  std::size_t found = 0, seen = 0;
  for_each_line(text, [&](std::size_t line, std::string_view s) {
    if (found == 0 && (s.starts_with("f ") || s.starts_with("f\t")) && seen++ == face) found = line;
  });
  return found;
}

}  // namespace

std::string degenerate_reason(const Mesh& mesh, const AreaOutOfRange& range) {
  if (range.too_large == 0 && range.too_small == 0) return " (zero or non-finite area)";
  Aabb box;
  for (const vec4& p : mesh.positions) box.grow(p);
  const vec4 size = box.extent();
  const double span =
      std::sqrt(double(size[0]) * size[0] + double(size[1]) * size[1] + double(size[2]) * size[2]);
  if (range.too_large >= range.too_small)
    return ": the coordinates are too large for float arithmetic: the triangle areas overflow "
           "(the mesh spans " +
           fmt(span) + "; edges must be shorter than about 4e9)";
  return ": the coordinates are too small for float arithmetic: the triangle areas underflow "
         "to 0 (the mesh spans " +
         fmt(span) + "; edges must be longer than about 1e-11)";
}

Mesh obj_to_mesh(const std::string& path, const std::string& file_text, Scene& scene,
                 int override_material) {
  // Without a byte-order mark; copied only when there is one (the text may be large).
  std::string stripped;
  const bool has_bom = file_text.starts_with(kUtf8Bom);
  if (has_bom) stripped = without_bom(file_text);
  const std::string& text = has_bom ? stripped : file_text;
  if (override_material >= 0 &&
      static_cast<std::size_t>(override_material) >= scene.materials.size())
    throw Error(path + ": override material " + std::to_string(override_material) +
                " does not exist");
  const ObjScan scan = scan_obj(path, text);
  if (scan.faces == 0) error_at(path, 0, 0, "no faces (an OBJ mesh needs at least one 'f' line)");

  // The material libraries matter only without an override.
  const bool overridden = override_material >= 0;
  MtlMaterials mtl;
  std::optional<fs::path> root;
  if (!overridden) {
    root = asset_root(path, scene.assets);
    for (const std::string& name : scan.material_names) mtl.try_emplace(name);
    if (!read_libraries(path, scan, mtl, root)) warn_unknown_usemtl(path, scan, mtl);
  }

  // The text already read is parsed, not the file again; rt2 reads the materials itself, so
  // tinyobjloader gets none. Polygons are kept whole, for PolygonTriangulator.
  tinyobj::ObjReaderConfig config;
  config.triangulate = false;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromString(text, "", config))
    error_at(path, 0, 0,
             "tinyobjloader: " + (reader.Error().empty() ? "cannot parse" : reader.Error()));
  // tinyobjloader's warnings are dropped: what they report is checked above, or here.
  for (const float v : reader.GetAttrib().vertices)
    if (!std::isfinite(v)) error_at(path, 0, 0, "vertex is not finite");

  FaceMaterials materials(scene, path, scan, mtl, override_material, std::move(root));
  Fallbacks fallbacks;
  Mesh mesh = assemble(path, reader, scan, materials, fallbacks);
  if (fallbacks.count > 0) {
    warn(location(path, face_line(text, fallbacks.first_face), 0) + ": a polygon of " +
         std::to_string(fallbacks.first_corners) +
         " corners intersects itself or is degenerate; ear clipping gave up and its last "
         "corners are a fan" +
         (fallbacks.count > 1
              ? " (" + std::to_string(fallbacks.count) + " such polygons in this file)"
              : ""));
  }
  const std::size_t faces = mesh.faces.size();
  const AreaOutOfRange range = area_out_of_range(mesh);  // before the faces go
  scene.degenerate_triangles += mesh.drop_degenerate();
  if (mesh.faces.empty()) {
    error_at(path, 0, 0,
             faces == 0 ? "no faces"
                        : "all " + std::to_string(faces) + " faces are degenerate" +
                              degenerate_reason(mesh, range));
  }
  return mesh;
}

}  // namespace rt2::io
