// rt2/io/gltf_scene.cpp — glTF 2.0 files into rt2::Scene (internal; see rt2/io/gltf_scene.h).
//
// tinygltf (Debian's libtinygltf, 2.7) parses the JSON, decodes data: URIs and reads the
// buffer files, through file-system callbacks of rt2's (regular files only, with a size
// limit, only under the glTF's folder) and an image callback that keeps the bytes
// undecoded (rt2 decodes images with OpenImageIO when it renders). tinygltf checks little
// of what it parses, so every index and byte range rt2 follows is checked here before use:
// accessors (Accessor below), the node graph (cycles, depth, instance count), materials,
// textures, cameras and lights. Messages name the element: "x.gltf: mesh 0 primitive 1:
// accessor 3 (POSITION): ...".
#include "rt2/io/gltf_scene.h"

#ifdef _OPENMP
#include <omp.h>
#endif
#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <exception>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rt2/base/error.h"
#include "rt2/base/memory.h"
#include "rt2/io/asset_path.h"
#include "rt2/io/framing.h"
#include "rt2/io/gltf_compression.h"
#include "rt2/io/gltf_document.h"
#include "rt2/io/text.h"

namespace rt2::io {

// A file as tinygltf parsed it, and what its first reading found that every pose shares.
struct ParsedGltf {
  tinygltf::Model model;
  bool quantized = false;  // KHR_mesh_quantization: integer texture coordinates as declared
  std::optional<std::vector<Animation>> animations;  // every animation, checked
  std::optional<Aabb> still;  // the bounds of the file's own node transforms (an animated file)
};

namespace {

namespace fs = std::filesystem;

// ---- loading through tinygltf -----------------------------------------------------------

// %XX escapes of a URI decoded (glTF URIs of files are percent-encoded).
std::string uri_decode(const std::string& uri) {
  std::string out;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    const auto hex = [](char c) {
      if (c >= '0' && c <= '9') return c - '0';
      if (c >= 'a' && c <= 'f') return c - 'a' + 10;
      if (c >= 'A' && c <= 'F') return c - 'A' + 10;
      return -1;
    };
    if (uri[i] == '%' && i + 2 < uri.size() && hex(uri[i + 1]) >= 0 && hex(uri[i + 2]) >= 0) {
      out += static_cast<char>(hex(uri[i + 1]) * 16 + hex(uri[i + 2]));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}


// What tinygltf may read: the glTF's buffers beside it (FsCallbacks::user_data).
struct Folder {
  std::string gltf;    // the glTF file
  std::string prefix;  // its folder and a '/', as tinygltf's JoinPath makes paths
  AssetPolicy policy;
};

// Only regular files that asset_file allows: tinygltf asks for paths it joined to the
// glTF's folder (and also looks in the current folder).
bool file_exists(const std::string& path, void* user) {
  const auto* folder = static_cast<const Folder*>(user);
  if (!path.starts_with(folder->prefix)) return false;
  try {
    std::error_code ec;
    return fs::is_regular_file(
        asset_file(folder->gltf, path.substr(folder->prefix.size()), folder->policy, ""), ec);
  } catch (const Error&) {
    return false;
  }
}

// No `~` or variable expansion (tinygltf's own uses wordexp on some systems).
std::string expand_file_path(const std::string& path, void*) { return path; }

// rt2's file reading: regular files only, at most kMaxGltfBytes; the message is tinygltf's err.
bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                     void*) {
  try {
    const std::string bytes = read_file(path, kMaxGltfBytes, "");
    out->assign(bytes.begin(), bytes.end());
    return true;
  } catch (const Error& e) {
    if (err) *err = e.what();
    return false;
  }
}

bool refuse_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err = "rt2 does not write files while loading";
  return false;
}

// The image callback: tinygltf calls it with the bytes of a data: URI, a file it read, or a
// bufferView (a pointer it computed without checking the view against the buffer). Only a
// data: URI's bytes are kept (in image->image, undecoded); a file is taken by its uri, and a
// bufferView's bytes are copied later, after their range is checked.
bool keep_undecoded(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                    const unsigned char* bytes, int size, void*) {
  if (image->bufferView >= 0 || !image->uri.empty()) return true;
  if (bytes != nullptr && size > 0) image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

// The first non-empty line of a tinygltf message, at most 300 characters.
std::string first_line(const std::string& msg) {
  std::size_t start = 0;
  while (start < msg.size()) {
    std::size_t end = msg.find('\n', start);
    if (end == std::string::npos) end = msg.size();
    std::string line = one_line(std::string_view(msg).substr(start, end - start));
    if (line.find_first_not_of(' ') != std::string::npos) {
      if (line.size() > 300) line = line.substr(0, 300) + "...";
      return line;
    }
    start = end + 1;
  }
  return "tinygltf could not parse it";
}

// The glTF model of `path`: checked and taken apart (gltf_document.h), read by tinygltf,
// its compressed parts decoded (gltf_compression.h). Every buffer file it names is checked
// with asset_file first, so that a refused one is named in rt2's words.
void parse_model(const std::string& path, const AssetPolicy& policy, tinygltf::Model& model,
                 bool& quantized) {
  const std::string bytes = read_file(path, kMaxGltfBytes, "");
  if (bytes.empty()) error_at(path, 0, 0, "file is empty");
  const GltfDocument doc = read_gltf_document(path, bytes);
  quantized = doc.quantized;
  for (std::size_t b = 0; b < doc.buffer_files.size(); ++b) {
    if (doc.buffer_files[b].empty()) continue;
    const std::string at = path + ": buffers[" + std::to_string(b) + "].uri";
    const std::string name = uri_decode(doc.buffer_files[b]);
    std::error_code ec;
    if (!fs::is_regular_file(asset_file(path, name, policy, at), ec))
      error_at(at, 0, 0,
               "'" + one_line(name) + "': " +
                   (fs::exists(fs::path(path).parent_path() / name, ec) ? "not a regular file"
                                                                        : "file not found"));
  }
  Folder folder{path, fs::path(path).parent_path().string(), policy};
  if (folder.prefix.empty()) folder.prefix = ".";
  const std::string base = folder.prefix;
  if (!folder.prefix.ends_with('/')) folder.prefix += '/';
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks(
      {&file_exists, &expand_file_path, &read_whole_file, &refuse_write, &folder});
  loader.SetImageLoader(&keep_undecoded, nullptr);
  std::string err, warn;
  const std::string input = tinygltf_bytes(doc);
  const auto* data = reinterpret_cast<const unsigned char*>(input.data());
  const auto size = static_cast<unsigned int>(input.size());
  const bool ok = doc.glb
                      ? loader.LoadBinaryFromMemory(&model, &err, &warn, data, size, base)
                      : loader.LoadASCIIFromString(&model, &err, &warn, input.data(), size, base);
  if (!ok) error_at(path, 0, 0, first_line(err));
  decode_compressed(path, doc, model);
}

// ---- transforms, in double ----------------------------------------------------------------

// A 4x4 matrix, column-major as glTF stores it: m[col * 4 + row] (rt2/scene/animation.h).
using Mat4 = Matrix4d;
constexpr Mat4 kIdentity = kIdentity4d;

struct Vec3d {
  double x = 0, y = 0, z = 0;
};

Vec3d transform_point(const Mat4& m, const Vec3d& p) {
  return {m[0] * p.x + m[4] * p.y + m[8] * p.z + m[12],
          m[1] * p.x + m[5] * p.y + m[9] * p.z + m[13],
          m[2] * p.x + m[6] * p.y + m[10] * p.z + m[14]};
}

Vec3d transform_vector(const Mat4& m, const Vec3d& v) {
  return {m[0] * v.x + m[4] * v.y + m[8] * v.z, m[1] * v.x + m[5] * v.y + m[9] * v.z,
          m[2] * v.x + m[6] * v.y + m[10] * v.z};
}

// The cofactor matrix of the upper 3x3 (det · inverse transpose), as a Mat4 without
// translation: it maps normals, and stays defined when the matrix is singular.
Mat4 cofactor(const Mat4& m) {
  const auto e = [&](int row, int col) { return m[col * 4 + row]; };
  Mat4 c{};
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col) {
      const int r0 = (row + 1) % 3, r1 = (row + 2) % 3, c0 = (col + 1) % 3, c1 = (col + 2) % 3;
      c[col * 4 + row] = e(r0, c0) * e(r1, c1) - e(r0, c1) * e(r1, c0);
    }
  c[15] = 1;
  return c;
}

double determinant3(const Mat4& m) {
  const Mat4 c = cofactor(m);
  return m[0] * c[0] + m[4] * c[4] + m[8] * c[8];
}

Vec3d normalized(const Vec3d& v) {
  const double len = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
  return {v.x / len, v.y / len, v.z / len};
}

bool finite3(const Vec3d& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Whether v is finite as floats too.
bool fits_float(const Vec3d& v) {
  return std::isfinite(float(v.x)) && std::isfinite(float(v.y)) && std::isfinite(float(v.z));
}

vec4 to_vec4(const Vec3d& v) { return vec4(float(v.x), float(v.y), float(v.z)); }

// Calls each(i) for every i in [0, n), on OpenMP's threads when n is large. Throws what the
// call of the lowest i that threw threw, as a serial loop would: each thread takes a run of
// consecutive indices and stops at its first throw.
template <class Each>
void for_each_index(std::size_t n, Each&& each) {
  constexpr std::size_t kSerialBelow = 1u << 14;
#ifdef _OPENMP
  if (n >= kSerialBelow) {
    std::size_t first = n;
    std::exception_ptr error;
#pragma omp parallel
    {
      const auto t = std::size_t(omp_get_thread_num()), threads = std::size_t(omp_get_num_threads());
      for (std::size_t i = n * t / threads, end = n * (t + 1) / threads; i < end; ++i) {
        try {
          each(i);
        } catch (...) {
#pragma omp critical(rt2_for_each_index)
          if (i < first) {
            first = i;
            error = std::current_exception();
          }
          break;
        }
      }
    }
    if (error) std::rethrow_exception(error);
    return;
  }
#endif
  for (std::size_t i = 0; i < n; ++i) each(i);
}

// ---- the loader ---------------------------------------------------------------------------

// "#3" or "#3 'name'", for messages.
// An element for messages: its index and its name, cut at 100 bytes (a name of a gigabyte
// would otherwise be copied into every message built while reading).
std::string named(int index, const std::string& name) {
  const std::string shown = name.size() > 100 ? name.substr(0, 100) + "..." : name;
  return "#" + std::to_string(index) + (name.empty() ? "" : " '" + one_line(shown) + "'");
}

// A checked accessor: element i starts at data + i * stride, holds `components` values of
// `component_size` bytes each, and lies within its buffer view and buffer.
struct Accessor {
  const unsigned char* data = nullptr;
  std::size_t count = 0, stride = 0;
  int component_type = 0, components = 0;
  std::size_t component_size = 0;
  bool normalized = false;

  // Component k of element i as a double: normalized integers mapped to [0, 1] (unsigned)
  // or [-1, 1] (signed: c / max, at least -1), as glTF 2.0 (3.11) maps them.
  double get(std::size_t i, int k) const {
    const unsigned char* p = data + i * stride + std::size_t(k) * component_size;
    const auto read = [p](auto v) {
      std::memcpy(&v, p, sizeof v);
      return v;
    };
    switch (component_type) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: return read(float{});
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? *p / 255.0 : *p;
      case TINYGLTF_COMPONENT_TYPE_BYTE: {
        const double c = read(std::int8_t{});
        return normalized ? std::max(c / 127.0, -1.0) : c;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        const double c = read(std::uint16_t{});
        return normalized ? c / 65535.0 : c;
      }
      case TINYGLTF_COMPONENT_TYPE_SHORT: {
        const double c = read(std::int16_t{});
        return normalized ? std::max(c / 32767.0, -1.0) : c;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return read(std::uint32_t{});
      default: return 0;
    }
  }
};

std::size_t component_size(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

const char* component_name(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "byte";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "unsigned byte";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "short";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "unsigned short";
    case TINYGLTF_COMPONENT_TYPE_INT: return "int";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "unsigned int";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "float";
    case TINYGLTF_COMPONENT_TYPE_DOUBLE: return "double";
    default: return "an unknown component type";
  }
}

int component_count(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
  }
}

// KHR_texture_transform of a texture reference: an affine map of glTF's (u, v), offset ·
// rotation · scale, u' = m[0] u + m[1] v + m[2], v' = m[3] u + m[4] v + m[5]. The rotation
// turns the image counter-clockwise as it appears (v down): u' = cos u + sin v,
// v' = -sin u + cos v, as Khronos' TextureTransformTest model checks.
struct UvTransform {
  std::array<double, 6> m = {1, 0, 0, 0, 1, 0};
  bool operator==(const UvTransform&) const = default;
};

// The transform of a textureInfo's extensions (identity without one); `tex_coord` becomes
// the set it overrides, if any.
UvTransform uv_transform(const tinygltf::ExtensionMap& exts, int& tex_coord) {
  UvTransform t;
  const auto it = exts.find("KHR_texture_transform");
  if (it == exts.end()) return t;
  const tinygltf::Value& x = it->second;
  const auto pair = [&](const char* key, double d0, double d1) {
    if (!x.Has(key)) return std::array<double, 2>{d0, d1};
    const tinygltf::Value& v = x.Get(key);
    return std::array<double, 2>{v.Get(0).GetNumberAsDouble(), v.Get(1).GetNumberAsDouble()};
  };
  const std::array<double, 2> offset = pair("offset", 0, 0), scale = pair("scale", 1, 1);
  const double r = x.Has("rotation") ? x.Get("rotation").GetNumberAsDouble() : 0.0;
  const double c = std::cos(r), sn = std::sin(r);
  t.m = {c * scale[0], sn * scale[1], offset[0], -sn * scale[0], c * scale[1], offset[1]};
  if (x.Has("texCoord")) tex_coord = x.Get("texCoord").GetNumberAsInt();
  return t;
}

// KHR_materials_pbrSpecularGlossiness as metallic-roughness, per the conversion Khronos'
// tools use: roughness = 1 - glossiness; metallic solved from the perceived brightness of
// the diffuse and specular colours (a dielectric reflects 4 %); the base colour blends the
// colour the diffuse term implies with the one the specular term implies by metallic².
struct MetallicRoughness {
  vec4 base_color;
  float metallic = 0, roughness = 1;
};

MetallicRoughness from_specular_glossiness(const std::array<double, 3>& diffuse,
                                           const std::array<double, 3>& specular,
                                           double glossiness) {
  constexpr double kDielectric = 0.04, kEpsilon = 1e-6;
  const auto brightness = [](const std::array<double, 3>& c) {
    return std::sqrt(0.299 * c[0] * c[0] + 0.587 * c[1] * c[1] + 0.114 * c[2] * c[2]);
  };
  const double one_minus_specular = 1.0 - std::max({specular[0], specular[1], specular[2]});
  const double d = brightness(diffuse), sp = brightness(specular);
  double metallic = 0;
  if (sp >= kDielectric) {
    const double a = kDielectric,
                 b = d * one_minus_specular / (1 - kDielectric) + sp - 2 * kDielectric,
                 c = kDielectric - sp;
    metallic = std::clamp((-b + std::sqrt(std::max(b * b - 4 * a * c, 0.0))) / (2 * a), 0.0, 1.0);
  }
  MetallicRoughness out;
  float rgb[3];
  for (int k = 0; k < 3; ++k) {
    const double from_diffuse = diffuse[std::size_t(k)] * one_minus_specular / (1 - kDielectric) /
                                std::max(1 - metallic, kEpsilon);
    const double from_specular =
        (specular[std::size_t(k)] - kDielectric * (1 - metallic)) / std::max(metallic, kEpsilon);
    const double m2 = metallic * metallic;
    rgb[k] = float(std::clamp(from_diffuse + (from_specular - from_diffuse) * m2, 0.0, 1.0));
  }
  out.base_color = vec4(rgb[0], rgb[1], rgb[2]);
  out.metallic = float(metallic);
  out.roughness = float(std::clamp(1.0 - glossiness, 0.0, 1.0));
  return out;
}

// What a glTF file is read into, and from.
class GltfReader {
 public:
  // `animate` false: the file's own node transforms and weights, whatever `pose` says.
  GltfReader(ParsedGltf& file, const std::string& path, const AssetPolicy& policy,
             const ScenePose& pose, bool animate = true)
      : path_(path), pose_(pose), animate_(animate), file_(file), model_(file.model),
        quantized_(file.quantized) {
    scene_.assets = policy;
  }

  Scene read();

 private:
  [[noreturn]] void fail(const std::string& msg) const { error_at(path_, 0, 0, msg); }
  void warn_once(const std::string& key, const std::string& msg);

  // The bytes [offset, offset + length) of buffer view `index`, checked.
  std::string_view view_bytes(int index, std::size_t offset, std::size_t length,
                              const std::string& what) const;
  Accessor accessor(int index, const std::string& what, std::initializer_list<int> types,
                    int components) const;

  Track track(const tinygltf::AnimationSampler& sampler, NodeProperty property, int targets,
              const std::string& at);
  int morph_targets(int mesh_index, const std::string& at);
  std::vector<double> morph_weights(int node, const std::string& at);
  Animation animation(int index);
  void pose_nodes();
  void read_skins();
  Mat4 node_world(int node, const std::string& at);
  const std::vector<Mat4>& joint_matrices(int skin);
  void walk(int root, const Mat4& parent);
  void add_primitive(int mesh_index, int prim_index, const Mat4& world,
                     const std::vector<double>& weights, Mesh* into = nullptr, int skin = -1);
  void place_meshes();
  void set_camera(int node, int camera_index, const Mat4& world);
  void add_light(int node, const tinygltf::Value& ext, const Mat4& world);
  void finish_lights(const Framing& frame);
  Framing still_framing();
  std::uint32_t material(int index);
  std::uint32_t texture(int index, bool srgb, int tex_coord, const std::string& what);

  std::string path_;
  ScenePose pose_;
  bool animate_;
  ParsedGltf& file_;
  const tinygltf::Model& model_;
  bool quantized_;  // KHR_mesh_quantization: integer texture coordinates as declared
  Scene scene_;
  std::vector<int> material_of_;  // glTF material -> scene material, or -1
  std::vector<UvTransform> uv_transforms_;  // per glTF material (material() fills it)
  int default_material_ = -1;
  std::map<std::pair<int, bool>, std::uint32_t> textures_;  // (image, srgb) -> scene texture
  std::vector<char> on_path_;  // nodes on the current walk (cycle check)
  std::vector<NodeTrs> posed_;  // per node, its transform as posed; empty: no animation
  std::size_t key_values_ = 0;  // keyframe numbers read, against kMaxGltfKeyValues
  std::size_t morph_reads_ = 0;  // vertices of targets read, against kMaxGltfMorphReads
  std::vector<int> morph_counts_;  // per mesh, its morph target count once known (else -1)
  // Per skin: its joints (nodes, checked), inverse bind matrices (checked affine) and, once a
  // skinned mesh needs them, its joint matrices as posed (joint world · inverse bind).
  struct Skin {
    std::vector<int> joints;
    std::vector<Mat4> inverse_bind, matrices;
  };
  std::vector<Skin> skins_;
  // The node tree read upwards, for joints' world matrices (node_world): per node its parent
  // (-1 none, -2 several), and its world matrix as posed once known.
  std::vector<int> parent_;
  std::vector<Mat4> world_;
  std::vector<char> world_known_;
  std::size_t visits_ = 0, primitives_ = 0, vertices_ = 0, triangles_ = 0;
  std::uint64_t memory_ = available_memory();  // what the triangles may take
  bool have_camera_ = false;
  std::vector<std::string> warned_;
  // Lights wait for the scene's bounds (their intensity is scaled at its centre).
  struct PendingLight {
    int index;
    Vec3d position, direction;
  };
  std::vector<PendingLight> lights_;
  // The nodes' meshes as the walk meets them: read once the walk has counted each mesh's uses.
  struct Placement {
    int mesh;
    Mat4 world;
    std::vector<double> weights;
    int skin;  // -1: none
  };
  std::vector<Placement> placements_;
};

void GltfReader::warn_once(const std::string& key, const std::string& msg) {
  if (std::find(warned_.begin(), warned_.end(), key) != warned_.end()) return;
  warned_.push_back(key);
  warn(path_ + ": " + msg);
}

std::string_view GltfReader::view_bytes(int index, std::size_t offset, std::size_t length,
                                        const std::string& what) const {
  if (index < 0 || std::size_t(index) >= model_.bufferViews.size())
    fail(what + ": bufferView " + std::to_string(index) + " does not exist (" +
         std::to_string(model_.bufferViews.size()) + " buffer views)");
  const tinygltf::BufferView& v = model_.bufferViews[std::size_t(index)];
  if (v.buffer < 0 || std::size_t(v.buffer) >= model_.buffers.size())
    fail(what + ": bufferView " + std::to_string(index) + " names buffer " +
         std::to_string(v.buffer) + ", which does not exist");
  const std::vector<unsigned char>& b = model_.buffers[std::size_t(v.buffer)].data;
  if (v.byteOffset > b.size() || v.byteLength > b.size() - v.byteOffset)
    fail(what + ": bufferView " + std::to_string(index) + " (bytes " +
         std::to_string(v.byteOffset) + " + " + std::to_string(v.byteLength) +
         ") lies beyond its buffer of " + std::to_string(b.size()) + " bytes");
  if (offset > v.byteLength || length > v.byteLength - offset)
    fail(what + ": bytes " + std::to_string(offset) + " + " + std::to_string(length) +
         " lie beyond bufferView " + std::to_string(index) + " of " + std::to_string(v.byteLength) +
         " bytes");
  return {reinterpret_cast<const char*>(b.data()) + v.byteOffset + offset, length};
}

Accessor GltfReader::accessor(int index, const std::string& what, std::initializer_list<int> types,
                              int components) const {
  const std::string at = what + ": accessor " + std::to_string(index);
  if (index < 0 || std::size_t(index) >= model_.accessors.size())
    fail(at + " does not exist (" + std::to_string(model_.accessors.size()) + " accessors)");
  const tinygltf::Accessor& a = model_.accessors[std::size_t(index)];
  if (a.sparse.isSparse) fail(at + ": sparse accessors are not supported");
  Accessor r;
  r.component_type = a.componentType;
  r.components = component_count(a.type);
  r.component_size = component_size(a.componentType);
  r.normalized = a.normalized;
  r.count = a.count;
  if (std::find(types.begin(), types.end(), a.componentType) == types.end()) {
    std::string expected;
    for (const int t : types)
      expected += std::string(expected.empty() ? "" : " or ") + component_name(t);
    fail(at + ": components are " + component_name(a.componentType) + ", expected " + expected);
  }
  if (r.components != components)
    fail(at + ": has " +
         (r.components ? std::to_string(r.components) : "an unsupported number of") +
         " components per element, expected " + std::to_string(components));
  if (a.bufferView < 0) fail(at + ": has no bufferView (all zeros), which rt2 does not read");
  if (r.count == 0) return r;
  const std::size_t element = r.component_size * std::size_t(r.components);
  const std::size_t view_stride = std::size_t(a.bufferView) < model_.bufferViews.size()
                                      ? model_.bufferViews[std::size_t(a.bufferView)].byteStride
                                      : 0;
  r.stride = view_stride ? view_stride : element;
  if (r.stride < element)
    fail(at + ": byteStride " + std::to_string(r.stride) + " is less than its element of " +
         std::to_string(element) + " bytes");
  if (r.count > kMaxGltfVertices || r.count - 1 > (std::size_t(1) << 40) / r.stride)
    fail(at + ": count " + std::to_string(r.count) + " is too large");
  const std::size_t length = r.stride * (r.count - 1) + element;
  r.data = reinterpret_cast<const unsigned char*>(
      view_bytes(a.bufferView, a.byteOffset, length, at).data());
  return r;
}

std::uint32_t GltfReader::texture(int index, bool srgb, int tex_coord, const std::string& what) {
  if (index < 0) return kNoTexture;
  const std::string at = what + ": texture " + std::to_string(index);
  if (std::size_t(index) >= model_.textures.size())
    fail(at + " does not exist (" + std::to_string(model_.textures.size()) + " textures)");
  if (tex_coord != 0)
    warn_once("texcoord", "a texture uses TEXCOORD_" + std::to_string(tex_coord) +
                              "; rt2 reads only TEXCOORD_0");
  const int image = model_.textures[std::size_t(index)].source;
  if (image < 0) {
    warn_once("no source", at + " has no source image (an extension's?); ignored");
    return kNoTexture;
  }
  if (std::size_t(image) >= model_.images.size())
    fail(at + ": image " + std::to_string(image) + " does not exist (" +
         std::to_string(model_.images.size()) + " images)");
  const auto key = std::pair(image, srgb);
  if (const auto it = textures_.find(key); it != textures_.end()) return it->second;
  const tinygltf::Image& img = model_.images[std::size_t(image)];
  const std::string image_at = "image " + std::to_string(image);
  TextureDesc t;
  t.srgb = srgb;
  if (img.bufferView >= 0) {
    const std::size_t length = model_.bufferViews.size() > std::size_t(img.bufferView)
                                   ? model_.bufferViews[std::size_t(img.bufferView)].byteLength
                                   : 0;
    t.data = std::string(view_bytes(img.bufferView, 0, length, image_at));
    t.path = fs::path(path_).filename().string() + ":" + image_at;
  } else if (!img.uri.empty()) {
    const std::string file = uri_decode(img.uri);
    const fs::path p = asset_file(path_, file, scene_.assets,
                                  path_ + ": images[" + std::to_string(image) + "].uri");
    std::error_code ec;
    const fs::file_status st = fs::status(p, ec);
    const std::string why = st.type() == fs::file_type::not_found   ? "No such file or directory"
                            : st.type() == fs::file_type::directory ? "is a directory"
                            : st.type() != fs::file_type::regular   ? "is not a regular file"
                                                                    : "";
    if (!why.empty()) fail(image_at + ": " + one_line(file) + ": " + why);
    t.path = p.string();
  } else {
    t.data.assign(img.image.begin(), img.image.end());
    t.path = fs::path(path_).filename().string() + ":" + image_at;
  }
  if (t.path.empty() || (t.data.empty() && img.uri.empty())) fail(image_at + " is empty");
  scene_.textures.push_back(std::move(t));
  const auto n = std::uint32_t(scene_.textures.size() - 1);
  textures_.emplace(key, n);
  return n;
}

// A number of an extension object, or `fallback`.
double ext_number(const tinygltf::ExtensionMap& exts, const char* ext, const char* key,
                  double fallback) {
  const auto it = exts.find(ext);
  if (it == exts.end() || !it->second.IsObject() || !it->second.Has(key)) return fallback;
  const tinygltf::Value& v = it->second.Get(key);
  return v.IsNumber() ? v.GetNumberAsDouble() : fallback;
}

std::uint32_t GltfReader::material(int index) {
  if (index < 0) {
    if (default_material_ < 0) {
      Material m;  // glTF's default material: white, metallic 1, roughness 1
      m.model = Shading::pbr;
      m.metallic = 1.0f;
      m.diffuse = m.base_color;
      default_material_ =
          int(scene_.add_material(fs::path(path_).filename().string() + ":default", m));
    }
    return std::uint32_t(default_material_);
  }
  if (std::size_t(index) >= model_.materials.size())
    fail("material " + std::to_string(index) + " does not exist (" +
         std::to_string(model_.materials.size()) + " materials)");
  if (material_of_.empty()) {
    material_of_.assign(model_.materials.size(), -1);
    uv_transforms_.assign(model_.materials.size(), UvTransform{});
  }
  if (material_of_[std::size_t(index)] >= 0) return std::uint32_t(material_of_[std::size_t(index)]);
  const tinygltf::Material& g = model_.materials[std::size_t(index)];
  const std::string at = "material " + named(index, g.name);
  const tinygltf::PbrMetallicRoughness& pbr = g.pbrMetallicRoughness;
  const auto colour = [&](const std::vector<double>& v, std::size_t n, const char* field) {
    if (v.size() != n)
      fail(at + ": " + field + " has " + std::to_string(v.size()) + " numbers, expected " +
           std::to_string(n));
    for (const double x : v)
      if (!(x >= 0 && x <= 1e6)) fail(at + ": " + field + " holds " + fmt(x) + ", expected >= 0");
    return vec4(float(v[0]), float(v[1]), float(v[2]));
  };
  const auto unit = [&](double v, const char* field) {
    if (!(v >= 0 && v <= 1)) fail(at + ": " + field + " is " + fmt(v) + ", expected 0..1");
    return float(v);
  };
  Material m;
  m.model = Shading::pbr;
  m.base_color = colour(pbr.baseColorFactor, 4, "baseColorFactor");  // alpha is ignored
  m.metallic = unit(pbr.metallicFactor, "metallicFactor");
  m.roughness = unit(pbr.roughnessFactor, "roughnessFactor");
  const double strength =
      ext_number(g.extensions, "KHR_materials_emissive_strength", "emissiveStrength", 1.0);
  if (!(strength >= 0 && strength <= 1e6)) fail(at + ": emissiveStrength is " + fmt(strength));
  m.emissive = colour(g.emissiveFactor, 3, "emissiveFactor") * float(strength);
  m.transmission =
      unit(ext_number(g.extensions, "KHR_materials_transmission", "transmissionFactor", 0.0),
           "transmissionFactor");
  const double ior = ext_number(g.extensions, "KHR_materials_ior", "ior", 1.5);
  if (!(ior >= 1 && ior <= 100)) fail(at + ": ior is " + fmt(ior) + ", expected 1..100");
  m.ior = float(ior);
  m.normal_scale = float(g.normalTexture.scale);
  if (!std::isfinite(m.normal_scale)) fail(at + ": normalTexture.scale is not finite");
  // The texture transform of the material's first transformed texture (texture coordinates
  // are transformed where they are read, one set per primitive).
  std::optional<UvTransform> uv;
  const auto tex = [&](const auto& info, bool srgb) {
    if (info.index < 0) return kNoTexture;
    int tex_coord = info.texCoord;
    const UvTransform t = uv_transform(info.extensions, tex_coord);
    if (!uv) uv = t;
    else if (!(*uv == t))
      warn_once("uv transforms", at + ": its textures have different KHR_texture_transform; "
                                      "the first one is applied to all");
    return texture(info.index, srgb, tex_coord, at);
  };
  m.base_color_texture = tex(pbr.baseColorTexture, true);
  m.metallic_roughness_texture = tex(pbr.metallicRoughnessTexture, false);
  m.normal_texture = tex(g.normalTexture, false);
  m.emissive_texture = tex(g.emissiveTexture, true);
  if (const auto it = g.extensions.find("KHR_materials_pbrSpecularGlossiness");
      it != g.extensions.end()) {
    const tinygltf::Value& x = it->second;
    const auto numbers = [&](const char* key, std::array<double, 4> v) {
      if (x.Has(key))
        for (std::size_t k = 0; k < x.Get(key).ArrayLen(); ++k)
          v[k] = x.Get(key).Get(int(k)).GetNumberAsDouble();
      return v;
    };
    const std::array<double, 4> diffuse = numbers("diffuseFactor", {1, 1, 1, 1});
    const std::array<double, 4> specular = numbers("specularFactor", {1, 1, 1, 0});
    const double gloss =
        x.Has("glossinessFactor") ? x.Get("glossinessFactor").GetNumberAsDouble() : 1.0;
    const MetallicRoughness mr = from_specular_glossiness(
        {diffuse[0], diffuse[1], diffuse[2]}, {specular[0], specular[1], specular[2]}, gloss);
    m.base_color = mr.base_color;
    m.metallic = mr.metallic;
    m.roughness = mr.roughness;
    m.metallic_roughness_texture = kNoTexture;
    if (x.Has("diffuseTexture")) {
      tinygltf::TextureInfo info;
      const tinygltf::Value& t = x.Get("diffuseTexture");
      info.index = t.Get("index").GetNumberAsInt();
      info.texCoord = t.Has("texCoord") ? t.Get("texCoord").GetNumberAsInt() : 0;
      if (t.Has("extensions") && t.Get("extensions").Has("KHR_texture_transform"))
        info.extensions["KHR_texture_transform"] = t.Get("extensions").Get("KHR_texture_transform");
      m.base_color_texture = tex(info, true);
    }
    if (x.Has("specularGlossinessTexture"))
      warn_once("specgloss texture", at + ": its specularGlossinessTexture is ignored (rt2 "
                                          "converts specular-glossiness factors only)");
  }
  uv_transforms_[std::size_t(index)] = uv.value_or(UvTransform{});
  // Phong fields, for renderers of Shading::phong: the base colour diffuse, a highlight as
  // tight as the roughness, metals mirror-like when smooth; the emission adds to Ka.
  const float alpha = std::max(m.roughness * m.roughness, 0.03f);
  m.diffuse = m.base_color * (1.0f - 0.5f * m.metallic);
  m.ambient = m.diffuse * 0.1f + m.emissive;
  m.specular = vec4(0.04f, 0.04f, 0.04f) * (1.0f - m.metallic) + m.base_color * m.metallic;
  m.shininess = std::min(2.0f / (alpha * alpha) - 2.0f, 1000.0f);
  m.reflectivity = m.metallic * (1.0f - m.roughness);
  m.transparency = m.transmission;
  const std::string name = fs::path(path_).filename().string() + ":" +
                           (g.name.empty() ? "#" + std::to_string(index) : one_line(g.name));
  material_of_[std::size_t(index)] = int(scene_.add_material(name, m));
  return std::uint32_t(material_of_[std::size_t(index)]);
}

// A node's own translation, rotation and scale (its matrix, when it has one, is not one).
NodeTrs node_trs(const tinygltf::Node& n) {
  NodeTrs trs;
  // (local_matrix refuses other sizes)
  if (n.translation.size() == 3) std::copy_n(n.translation.begin(), 3, trs.translation.begin());
  if (n.rotation.size() == 4) std::copy_n(n.rotation.begin(), 4, trs.rotation.begin());
  if (n.scale.size() == 3) std::copy_n(n.scale.begin(), 3, trs.scale.begin());
  return trs;
}

// A node's local matrix: `matrix`, or translation · rotation · scale, those of `posed` (the
// node as an animation poses it) when given.
Mat4 local_matrix(const tinygltf::Node& n, const NodeTrs* posed, const std::string& at) {
  const auto check = [&](const std::vector<double>& v, std::size_t size, const char* field) {
    if (!v.empty() && v.size() != size)
      error_at(at, 0, 0,
               std::string(field) + " has " + std::to_string(v.size()) + " numbers, expected " +
                   std::to_string(size));
    for (const double x : v)
      if (!std::isfinite(x)) error_at(at, 0, 0, std::string(field) + " holds " + fmt(x));
  };
  check(n.matrix, 16, "matrix");
  check(n.translation, 3, "translation");
  check(n.rotation, 4, "rotation");
  check(n.scale, 3, "scale");
  if (!n.matrix.empty()) {
    Mat4 m;
    std::copy(n.matrix.begin(), n.matrix.end(), m.begin());
    return m;
  }
  const NodeTrs trs = posed ? *posed : node_trs(n);
  const std::array<double, 4>& q = trs.rotation;
  if (!(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3] > 0))
    error_at(at, 0, 0, posed ? "its animated rotation is a zero quaternion"
                             : "rotation is a zero quaternion");
  return matrix_of(trs);
}

// The keys of `sampler` for a node's `property` (`targets`: its mesh's morph target count,
// for weights), checked: times finite and strictly increasing, one value (three for a cubic
// spline) per time, every number finite.
Track GltfReader::track(const tinygltf::AnimationSampler& sampler, NodeProperty property,
                        int targets, const std::string& at) {
  Track t;
  t.property = property;
  t.width = key_width(property, targets);
  if (sampler.interpolation == "STEP")
    t.interpolation = Interpolation::step;
  else if (sampler.interpolation == "CUBICSPLINE")
    t.interpolation = Interpolation::cubic_spline;
  else if (sampler.interpolation != "LINEAR")
    fail(at + ": interpolation '" + one_line(sampler.interpolation) + "' is not one of glTF's");
  const Accessor in = accessor(sampler.input, at + " input", {TINYGLTF_COMPONENT_TYPE_FLOAT}, 1);
  const std::size_t width = std::size_t(t.width);
  // Rotations and weights may be normalized integers (glTF 2.0 3.11); positions and scales
  // are floats. Weights are scalars, `width` of them a key.
  const bool integers = property == NodeProperty::rotation || property == NodeProperty::weights;
  const Accessor out =
      integers ? accessor(sampler.output, at + " output",
                          {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
                           TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT,
                           TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                          property == NodeProperty::weights ? 1 : 4)
               : accessor(sampler.output, at + " output", {TINYGLTF_COMPONENT_TYPE_FLOAT}, 3);
  if (out.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT && !out.normalized)
    fail(at + ": output: integer " + (property == NodeProperty::weights ? "weights" : "rotations") +
         " must be normalized");
  if (in.count == 0) fail(at + ": input has no keys");
  const std::size_t per_key = t.interpolation == Interpolation::cubic_spline ? 3 : 1;
  const std::size_t elements_per_key = per_key * (property == NodeProperty::weights ? width : 1);
  if (out.count != in.count * elements_per_key)
    fail(at + ": output has " + std::to_string(out.count) + " elements for " +
         std::to_string(in.count) + " keys, expected " +
         std::to_string(in.count * elements_per_key) +
         (per_key == 3 ? " (CUBICSPLINE: in-tangent, value, out-tangent per key)" : "") +
         (property == NodeProperty::weights
              ? " (" + std::to_string(width) + " morph target weights per key)"
              : ""));
  key_values_ += in.count + in.count * per_key * width;
  if (key_values_ > kMaxGltfKeyValues)
    fail("its animations hold more than " + std::to_string(kMaxGltfKeyValues) +
         " keyframe numbers");
  t.times.resize(in.count);
  for (std::size_t i = 0; i < in.count; ++i) {
    t.times[i] = in.get(i, 0);
    if (!std::isfinite(t.times[i]))
      fail(at + ": input key " + std::to_string(i) + " is " + fmt(t.times[i]));
    if (i > 0 && !(t.times[i] > t.times[i - 1]))
      fail(at + ": input key " + std::to_string(i) + " (" + fmt(t.times[i]) +
           " s) does not come after key " + std::to_string(i - 1) + " (" +
           fmt(t.times[i - 1]) + " s); key times must increase");
  }
  const std::size_t groups = in.count * per_key;  // groups of `width` numbers
  t.values.resize(groups * width);
  for (std::size_t g = 0; g < groups; ++g) {
    double length2 = 0;
    for (std::size_t k = 0; k < width; ++k) {
      // a group is one element of a vector accessor, or `width` scalars
      const double v = property == NodeProperty::weights ? out.get(g * width + k, 0)
                                                         : out.get(g, int(k));
      if (!std::isfinite(v))
        fail(at + ": output element " +
             std::to_string(property == NodeProperty::weights ? g * width + k : g) + " holds " +
             fmt(v));
      t.values[g * width + k] = v;
      length2 += v * v;
    }
    const bool is_value = per_key == 1 || g % 3 == 1;  // not a cubic spline's tangent
    if (property == NodeProperty::rotation && is_value && !(length2 > 0))
      fail(at + ": output element " + std::to_string(g) + " is a zero quaternion");
  }
  return t;
}

// Animation `index` of the file, its channels and samplers checked.
Animation GltfReader::animation(int index) {
  const tinygltf::Animation& a = model_.animations[std::size_t(index)];
  Animation result;
  result.name = a.name.empty() ? "#" + std::to_string(index) : one_line(a.name);
  const std::string at = "animation " + named(index, a.name);
  std::vector<std::uint8_t> targeted(model_.nodes.size() * 4, 0);  // per node and property
  for (std::size_t c = 0; c < a.channels.size(); ++c) {
    const tinygltf::AnimationChannel& ch = a.channels[c];
    const std::string c_at = at + " channel " + std::to_string(c);
    if (ch.sampler < 0 || std::size_t(ch.sampler) >= a.samplers.size())
      fail(c_at + ": sampler " + std::to_string(ch.sampler) + " does not exist (" +
           std::to_string(a.samplers.size()) + " samplers)");
    if (ch.target_node < 0) continue;  // glTF: no node, nothing to animate
    if (std::size_t(ch.target_node) >= model_.nodes.size())
      fail(c_at + ": node " + std::to_string(ch.target_node) + " does not exist (" +
           std::to_string(model_.nodes.size()) + " nodes)");
    NodeProperty property;
    if (ch.target_path == "translation")
      property = NodeProperty::translation;
    else if (ch.target_path == "rotation")
      property = NodeProperty::rotation;
    else if (ch.target_path == "scale")
      property = NodeProperty::scale;
    else if (ch.target_path == "weights")
      property = NodeProperty::weights;
    else {
      warn_once("anim-" + ch.target_path,
                "animated " + one_line(ch.target_path) + " stay still (rt2 animates node "
                "translation, rotation, scale and morph target weights)");
      continue;
    }
    const tinygltf::Node& node = model_.nodes[std::size_t(ch.target_node)];
    int morph = 0;
    if (property == NodeProperty::weights) {
      if (node.mesh < 0 || std::size_t(node.mesh) >= model_.meshes.size())
        fail(c_at + ": animates the weights of node " + named(ch.target_node, node.name) +
             ", which has no mesh");
      morph = morph_targets(node.mesh, c_at);
      if (morph == 0)
        fail(c_at + ": animates the weights of node " + named(ch.target_node, node.name) +
             ", whose mesh has no morph targets");
    }
    if (!node.matrix.empty())
      fail(c_at + ": node " + named(ch.target_node, node.name) +
           " has a matrix, and glTF allows only nodes without one to be animated");
    std::uint8_t& seen = targeted[std::size_t(ch.target_node) * 4 + std::size_t(property)];
    if (seen)
      fail(c_at + ": node " + std::to_string(ch.target_node) + " " + ch.target_path +
           " is the target of an earlier channel; glTF allows one per animation");
    seen = 1;
    result.channels.push_back(
        {ch.target_node, track(a.samplers[std::size_t(ch.sampler)], property, morph,
                               c_at + " (sampler " + std::to_string(ch.sampler) + ")")});
  }
  return result;
}

// Checks every animation, lists them in the scene, and poses the nodes as the one `pose_`
// names is at `pose_.seconds`.
void GltfReader::pose_nodes() {
  int chosen = -1;
  const std::string& want = pose_.animation;
  if (!want.empty()) {
    if (model_.animations.empty()) fail("has no animations (asked for '" + one_line(want) + "')");
    const bool digits = want.find_first_not_of("0123456789") == std::string::npos;
    for (std::size_t i = 0; i < model_.animations.size() && chosen < 0; ++i)
      if (model_.animations[i].name == want) chosen = int(i);
    if (chosen < 0 && digits && want.size() < 10 &&
        std::stoul(want) < model_.animations.size())
      chosen = int(std::stoul(want));
    if (chosen < 0) {
      std::string names;
      for (std::size_t i = 0; i < model_.animations.size() && i < 8; ++i)
        names += (i ? ", " : "") + named(int(i), model_.animations[i].name);
      fail("has no animation '" + one_line(want) + "' (its " +
           std::to_string(model_.animations.size()) + ": " + names +
           (model_.animations.size() > 8 ? ", ..." : "") + ")");
    }
  } else if (!model_.animations.empty()) {
    chosen = 0;
  }
  if (!animate_) chosen = -1;
  if (!std::isfinite(pose_.seconds)) fail("the time " + fmt(pose_.seconds) + " is not finite");
  if (!file_.animations) {  // checked once per file
    std::vector<Animation> all;
    for (std::size_t i = 0; i < model_.animations.size(); ++i) all.push_back(animation(int(i)));
    file_.animations = std::move(all);
  }
  for (std::size_t i = 0; i < model_.animations.size(); ++i) {
    const Animation& a = (*file_.animations)[i];
    scene_.animations.push_back({a.name, a.duration()});
    if (int(i) != chosen) continue;
    posed_.resize(model_.nodes.size());
    for (std::size_t n = 0; n < model_.nodes.size(); ++n) posed_[n] = node_trs(model_.nodes[n]);
    a.pose(pose_.seconds, posed_);
  }
  scene_.animation = chosen;
  scene_.seconds = pose_.seconds;
}

// The morph target count of mesh `mesh_index` (every primitive must have the same),
// counted once per mesh.
int GltfReader::morph_targets(int mesh_index, const std::string& at) {
  if (morph_counts_.empty()) morph_counts_.assign(model_.meshes.size(), -1);
  int& known = morph_counts_[std::size_t(mesh_index)];
  if (known >= 0) return known;
  const tinygltf::Mesh& m = model_.meshes[std::size_t(mesh_index)];
  const std::size_t n = m.primitives.empty() ? 0 : m.primitives[0].targets.size();
  for (const tinygltf::Primitive& p : m.primitives)
    if (p.targets.size() != n)
      fail(at + ": mesh " + named(mesh_index, m.name) +
           ": its primitives have different numbers of morph targets");
  if (n > kMaxGltfMorphTargets)
    fail(at + ": mesh " + named(mesh_index, m.name) + " has " + std::to_string(n) +
         " morph targets, more than " + std::to_string(kMaxGltfMorphTargets));
  known = int(n);
  return known;
}

// The morph target weights of node `node`'s mesh as posed: animated, else the node's, else
// the mesh's, else zeros; one per target.
std::vector<double> GltfReader::morph_weights(int node, const std::string& at) {
  const tinygltf::Node& n = model_.nodes[std::size_t(node)];
  const tinygltf::Mesh& m = model_.meshes[std::size_t(n.mesh)];
  const std::size_t targets = std::size_t(morph_targets(n.mesh, at));
  const auto check = [&](const std::vector<double>& w, const std::string& whose) {
    if (w.size() != targets)
      fail(at + ": " + whose + " has " + std::to_string(w.size()) + " morph target weights, its mesh " +
           std::to_string(targets) + " targets");
    for (const double x : w)
      if (!std::isfinite(x)) fail(at + ": " + whose + " has a weight of " + fmt(x));
    return w;
  };
  if (!posed_.empty() && !posed_[std::size_t(node)].weights.empty())
    return posed_[std::size_t(node)].weights;  // checked where the track was read
  if (!n.weights.empty()) return check(n.weights, "the node");
  if (!m.weights.empty()) return check(m.weights, "mesh " + named(n.mesh, m.name));
  return std::vector<double>(targets, 0.0);
}

// Every skin, checked whether a node uses it or not: its joints name nodes; its
// inverseBindMatrices (absent: identities) are float MAT4s, one per joint at least, finite
// and affine.
void GltfReader::read_skins() {
  // A float matrix whose last row an exporter wrote as 0 0 0 1, or computed by inverting in
  // float, is within 1e-7 or so of it; 1e-5 leaves room and refuses projections. The last row
  // is then taken as exactly 0 0 0 1.
  constexpr double kAffine = 1e-5;
  skins_.resize(model_.skins.size());
  for (std::size_t k = 0; k < model_.skins.size(); ++k) {
    const tinygltf::Skin& g = model_.skins[k];
    const std::string at = "skin " + named(int(k), g.name);
    Skin& skin = skins_[k];
    for (std::size_t j = 0; j < g.joints.size(); ++j)
      if (g.joints[j] < 0 || std::size_t(g.joints[j]) >= model_.nodes.size())
        fail(at + ": joints[" + std::to_string(j) + "]: node " + std::to_string(g.joints[j]) +
             " does not exist (" + std::to_string(model_.nodes.size()) + " nodes)");
    skin.joints = g.joints;
    skin.inverse_bind.assign(g.joints.size(), kIdentity);
    if (g.inverseBindMatrices < 0) continue;
    const std::string m_at = at + " inverseBindMatrices";
    const Accessor ibm = accessor(g.inverseBindMatrices, m_at, {TINYGLTF_COMPONENT_TYPE_FLOAT}, 16);
    if (ibm.count < g.joints.size())
      fail(m_at + " has " + std::to_string(ibm.count) + " elements, its skin " +
           std::to_string(g.joints.size()) + " joints");
    for (std::size_t j = 0; j < g.joints.size(); ++j) {
      Mat4& m = skin.inverse_bind[j];
      for (int e = 0; e < 16; ++e) {
        m[std::size_t(e)] = ibm.get(j, e);
        if (!std::isfinite(m[std::size_t(e)]))
          fail(m_at + " element " + std::to_string(j) + " holds " + fmt(m[std::size_t(e)]));
      }
      if (!(std::abs(m[3]) <= kAffine && std::abs(m[7]) <= kAffine && std::abs(m[11]) <= kAffine &&
            std::abs(m[15] - 1) <= kAffine))
        fail(m_at + " element " + std::to_string(j) + " is not affine (its last row is " +
             fmt(m[3]) + " " + fmt(m[7]) + " " + fmt(m[11]) + " " + fmt(m[15]) +
             ", expected 0 0 0 1)");
      m[3] = m[7] = m[11] = 0;
      m[15] = 1;
    }
  }
}

// Node `node`'s world matrix as posed, found by following its parents up to a root (glTF
// gives a node one parent at most; a joint's world matrix needs it).
Mat4 GltfReader::node_world(int node, const std::string& at) {
  if (parent_.empty()) {
    parent_.assign(model_.nodes.size(), -1);
    for (std::size_t p = 0; p < model_.nodes.size(); ++p)
      for (const int c : model_.nodes[p].children)
        if (c >= 0 && std::size_t(c) < parent_.size())
          parent_[std::size_t(c)] = parent_[std::size_t(c)] == -1 ? int(p) : -2;
    world_.resize(model_.nodes.size());
    world_known_.assign(model_.nodes.size(), 0);
  }
  std::vector<int> chain;  // from `node` up to a root or a node of known world matrix
  int k = node;
  while (k >= 0 && !world_known_[std::size_t(k)]) {
    const std::string k_at = "node " + named(k, model_.nodes[std::size_t(k)].name);
    if (parent_[std::size_t(k)] == -2)
      fail(at + ": " + k_at + " has several parents, so no one world matrix (glTF allows one)");
    if (chain.size() > std::size_t(kMaxGltfDepth))
      fail(at + ": " + k_at + " is nested more than " + std::to_string(kMaxGltfDepth) +
           " deep, or is its own ancestor (a cycle)");
    chain.push_back(k);
    k = parent_[std::size_t(k)];
  }
  Mat4 world = k >= 0 ? world_[std::size_t(k)] : kIdentity;
  for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
    const std::size_t n = std::size_t(*it);
    const NodeTrs* posed = posed_.empty() ? nullptr : &posed_[n];
    world = world * local_matrix(model_.nodes[n], posed,
                                 path_ + ": node " + named(*it, model_.nodes[n].name));
    world_[n] = world;
    world_known_[n] = 1;
  }
  return world_[std::size_t(node)];
}

// Skin `skin`'s joint matrices as posed (glTF 2.0 3.7.3): joint j's world matrix times its
// inverse bind matrix, which together take a vertex of the mesh into the world.
const std::vector<Mat4>& GltfReader::joint_matrices(int skin) {
  Skin& s = skins_[std::size_t(skin)];
  if (s.matrices.empty()) {
    const std::string at = "skin " + named(skin, model_.skins[std::size_t(skin)].name);
    for (std::size_t j = 0; j < s.joints.size(); ++j)
      s.matrices.push_back(node_world(s.joints[j], at + " joints[" + std::to_string(j) + "]") *
                           s.inverse_bind[j]);
  }
  return s.matrices;
}

void GltfReader::walk(int root, const Mat4& parent) {
  // Depth first with an explicit stack, nodes in the order a recursion would visit them (a
  // recursion 1024 deep overflowed the stack of the AddressSanitizer build).
  struct Frame {
    int node;
    Mat4 world;
    std::size_t next_child;
  };
  std::vector<Frame> stack;
  const auto enter = [&](int node, const Mat4& up) {
    if (node < 0 || std::size_t(node) >= model_.nodes.size())
      fail("node " + std::to_string(node) + " does not exist (" +
           std::to_string(model_.nodes.size()) + " nodes)");
    const tinygltf::Node& n = model_.nodes[std::size_t(node)];
    const std::string at = "node " + named(node, n.name);
    if (on_path_[std::size_t(node)]) fail(at + " is its own descendant (a cycle)");
    if (stack.size() > std::size_t(kMaxGltfDepth))
      fail(at + " is nested more than " + std::to_string(kMaxGltfDepth) + " deep");
    if (++visits_ > kMaxGltfNodeVisits)
      fail("more than " + std::to_string(kMaxGltfNodeVisits) +
           " node instances (nodes shared by many parents)");
    const NodeTrs* posed = posed_.empty() ? nullptr : &posed_[std::size_t(node)];
    const Mat4 world = up * local_matrix(n, posed, path_ + ": " + at);
    if (n.camera >= 0 && !have_camera_) set_camera(node, n.camera, world);
    if (const auto it = n.extensions.find("KHR_lights_punctual"); it != n.extensions.end())
      add_light(node, it->second, world);
    if (n.mesh >= 0) {
      if (std::size_t(n.mesh) >= model_.meshes.size())
        fail(at + ": mesh " + std::to_string(n.mesh) + " does not exist (" +
             std::to_string(model_.meshes.size()) + " meshes)");
      if (n.skin >= 0 && std::size_t(n.skin) >= skins_.size())
        fail(at + ": skin " + std::to_string(n.skin) + " does not exist (" +
             std::to_string(skins_.size()) + " skins)");
      placements_.push_back({n.mesh, world, morph_weights(node, at), n.skin});
    }
    on_path_[std::size_t(node)] = 1;
    stack.push_back({node, world, 0});
  };
  enter(root, parent);
  while (!stack.empty()) {
    Frame& f = stack.back();
    const std::vector<int>& children = model_.nodes[std::size_t(f.node)].children;
    if (f.next_child < children.size()) {
      const int child = children[f.next_child++];
      const Mat4 world = f.world;  // push_back may move the frame
      enter(child, world);
    } else {
      on_path_[std::size_t(f.node)] = 0;
      stack.pop_back();
    }
  }
}

// A mesh that two or more nodes place, without morph targets (whose weights are per node),
// is read once in its own coordinates and placed by instances (rt2/scene/instance.h); a
// mesh placed once is read into the world, where one tree over all such meshes traces
// faster than a tree per mesh. A node whose transform cannot be inverted (a scale of 0,
// which hides it) or would take its triangles beyond float arithmetic is read into the
// world too, where its degenerate triangles are dropped. A skinned node's vertices are its
// own (its joints place each one): it is always read into the world, and not counted among
// its mesh's uses, so the mesh's plain nodes may still share it.
void GltfReader::place_meshes() {
  std::vector<int> uses(model_.meshes.size(), 0);
  for (const Placement& p : placements_)
    if (p.skin < 0) ++uses[std::size_t(p.mesh)];
  // glTF mesh -> instanced mesh: -1 not read yet, -2 nothing to place
  std::vector<int> instanced(model_.meshes.size(), -1);
  std::vector<AreaRange> areas;
  for (const Placement& p : placements_) {
    const std::size_t m = std::size_t(p.mesh);
    const std::size_t primitives = model_.meshes[m].primitives.size();
    if (p.skin >= 0) {
      for (std::size_t k = 0; k < primitives; ++k)
        add_primitive(p.mesh, int(k), p.world, p.weights, nullptr, p.skin);
      continue;
    }
    Affine a;
    for (std::size_t r = 0; r < 3; ++r)
      for (std::size_t c = 0; c < 4; ++c) a.m[r][c] = p.world[c * 4 + r];
    bool share = uses[m] > 1 && p.weights.empty() && std::isnormal(a.determinant()) &&
                 a.inverse().finite();
    if (share && instanced[m] == -1) {
      Mesh merged;
      merged.name = fs::path(path_).filename().string() + ":mesh " + named(p.mesh, model_.meshes[m].name);
      for (std::size_t k = 0; k < primitives; ++k)
        add_primitive(p.mesh, int(k), kIdentity, p.weights, &merged);
      instanced[m] = merged.faces.empty() ? -2 : int(scene_.instanced_meshes.size());
      if (instanced[m] >= 0) {
        areas.push_back(area_range(merged));
        scene_.instanced_meshes.push_back(std::move(merged));
      }
    }
    if (share && instanced[m] == -2) continue;
    share = share && areas_fit_float(areas[std::size_t(instanced[m])], a);
    if (!share) {
      for (std::size_t k = 0; k < primitives; ++k) add_primitive(p.mesh, int(k), p.world, p.weights);
      continue;
    }
    Instance in;
    in.mesh = std::uint32_t(instanced[m]);
    in.to_world = a;
    scene_.instances.push_back(in);
  }
  placements_.clear();
}

void GltfReader::add_primitive(int mesh_index, int prim_index, const Mat4& world,
                               const std::vector<double>& weights, Mesh* into, int skin) {
  const tinygltf::Mesh& gm = model_.meshes[std::size_t(mesh_index)];
  const tinygltf::Primitive& prim = gm.primitives[std::size_t(prim_index)];
  const std::string at =
      "mesh " + named(mesh_index, gm.name) + " primitive " + std::to_string(prim_index);
  const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
  if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
      mode != TINYGLTF_MODE_TRIANGLE_FAN) {
    warn_once("mode", at + ": mode " + std::to_string(mode) +
                          " (points or lines) is skipped; rt2 draws triangles only");
    return;
  }
  const auto attribute = [&](const char* name) {
    const auto it = prim.attributes.find(name);
    return it == prim.attributes.end() ? -1 : it->second;
  };
  if (++primitives_ > kMaxGltfPrimitives)
    fail("more than " + std::to_string(kMaxGltfPrimitives) +
         " primitive instances (meshes of nodes shared by many parents?)");
  const std::uint32_t scene_material = material(prim.material);
  const UvTransform uv_transform =
      prim.material >= 0 ? uv_transforms_[std::size_t(prim.material)] : UvTransform{};
  const int pos_index = attribute("POSITION");
  if (pos_index < 0) fail(at + ": has no POSITION attribute");
  // KHR_mesh_quantization allows integer positions, normals and texture coordinates.
  const Accessor pos =
      accessor(pos_index, at + " POSITION",
               {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
                TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT,
                TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
               3);
  if (vertices_ + pos.count > kMaxGltfVertices)
    fail("more than " + std::to_string(kMaxGltfVertices) + " vertices in all mesh instances");
  vertices_ += pos.count;

  // Morph targets (glTF 2.0 3.7.2.2): POSITION and NORMAL are the base plus the sum of
  // weight x target, in the mesh's own space; a target of weight 0 is not read.
  struct Morph {
    double weight;
    std::optional<Accessor> position, normal;
  };
  std::vector<Morph> morphs;
  for (std::size_t k = 0; k < prim.targets.size(); ++k) {
    if (weights[k] == 0.0) continue;
    Morph m{weights[k], {}, {}};
    const std::string t_at = at + " target " + std::to_string(k);
    for (const auto& [name, index] : prim.targets[k]) {
      if (name != "POSITION" && name != "NORMAL") continue;  // TEXCOORD_n, TANGENT: unused
      const Accessor a = accessor(index, t_at + " " + name,
                                  {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
                                   TINYGLTF_COMPONENT_TYPE_SHORT},
                                  3);
      if (a.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT && !a.normalized)
        fail(t_at + " " + name + ": integer displacements must be normalized");
      if (a.count != pos.count)
        fail(t_at + " " + name + " has " + std::to_string(a.count) + " elements, POSITION " +
             std::to_string(pos.count));
      (name == "POSITION" ? m.position : m.normal) = a;
    }
    morph_reads_ += pos.count;
    if (morph_reads_ > kMaxGltfMorphReads)
      fail("its morph targets of non-zero weight, over all mesh instances, hold more than " +
           std::to_string(kMaxGltfMorphReads) + " vertices");
    morphs.push_back(std::move(m));
  }
  // Element i of `base` with the targets' `displacement` (position or normal) added.
  const auto morphed = [&](const Accessor& base, std::optional<Accessor> Morph::*displacement,
                           std::size_t i) {
    Vec3d v{base.get(i, 0), base.get(i, 1), base.get(i, 2)};
    for (const Morph& m : morphs)
      if (const std::optional<Accessor>& d = m.*displacement) {
        v.x += m.weight * d->get(i, 0);
        v.y += m.weight * d->get(i, 1);
        v.z += m.weight * d->get(i, 2);
      }
    return v;
  };

  // Skinning (glTF 2.0 3.7.3): vertex i is placed by the sum over its four joints of
  // weight x joint matrix (the node's own world matrix is ignored), after morphing. Weights
  // are >= 0 and sum to 1 within the tolerance of their type; they are divided by their sum.
  // A joint of weight 0 is not read. Four joints a vertex: JOINTS_1 and WEIGHTS_1 are refused.
  const std::vector<Mat4>* joints = skin >= 0 ? &joint_matrices(skin) : nullptr;
  std::optional<Accessor> joint_index, joint_weight;
  double weight_tolerance = 0;
  const std::string skin_at =
      skin >= 0 ? "skin " + named(skin, model_.skins[std::size_t(skin)].name) : "";
  if (joints) {
    if (attribute("JOINTS_1") >= 0 || attribute("WEIGHTS_1") >= 0)
      fail(at + ": has JOINTS_1 or WEIGHTS_1; rt2 reads four joints a vertex (JOINTS_0, "
                "WEIGHTS_0)");
    const int j_index = attribute("JOINTS_0"), w_index = attribute("WEIGHTS_0");
    if (j_index < 0 || w_index < 0)
      fail(at + ": its node has " + skin_at + ", but it has no " +
           (j_index < 0 ? "JOINTS_0" : "WEIGHTS_0") + " attribute");
    joint_index = accessor(j_index, at + " JOINTS_0",
                           {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                            TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                           4);
    if (joint_index->normalized) fail(at + ": JOINTS_0: joint indices must not be normalized");
    joint_weight = accessor(w_index, at + " WEIGHTS_0",
                            {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                             TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                            4);
    if (joint_weight->component_type != TINYGLTF_COMPONENT_TYPE_FLOAT && !joint_weight->normalized)
      fail(at + ": WEIGHTS_0: integer weights must be normalized");
    for (const Accessor* a : {&*joint_index, &*joint_weight})
      if (a->count != pos.count)
        fail(at + ": " + (a == &*joint_index ? "JOINTS_0" : "WEIGHTS_0") + " has " +
             std::to_string(a->count) + " elements, POSITION " + std::to_string(pos.count));
    // Float weights normalized in float sum to 1 within a few ulps; 2e-3 also lets through
    // weights an exporter wrote with three decimals, and refuses weights never normalized.
    // Four normalized integers, each rounded (at most half a step off) or truncated (less
    // than a step), sum to 1 within 4 steps.
    weight_tolerance = joint_weight->component_type == TINYGLTF_COMPONENT_TYPE_FLOAT ? 2e-3
                       : joint_weight->component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE
                           ? 4.0 / 255
                           : 4.0 / 65535;
  }
  // The matrix that places vertex i: the node's world matrix, or its joints' blend.
  const auto vertex_matrix = [&](std::size_t i) {
    if (!joints) return world;
    std::array<double, 4> w;
    double sum = 0;
    for (int k = 0; k < 4; ++k) {
      w[std::size_t(k)] = joint_weight->get(i, k);
      if (!(w[std::size_t(k)] >= 0) || !std::isfinite(w[std::size_t(k)]))
        fail(at + ": WEIGHTS_0 " + std::to_string(i) + " holds " + fmt(w[std::size_t(k)]) +
             ", expected a weight >= 0");
      sum += w[std::size_t(k)];
    }
    if (!(std::abs(sum - 1) <= weight_tolerance))
      fail(at + ": WEIGHTS_0 " + std::to_string(i) + " sums to " + fmt(sum) +
           ", expected 1 (within " + fmt(weight_tolerance) + ")");
    Mat4 m{};
    for (int k = 0; k < 4; ++k) {
      if (w[std::size_t(k)] == 0) continue;
      const double j = joint_index->get(i, k);
      if (!(j < double(joints->size())))
        fail(at + ": JOINTS_0 " + std::to_string(i) + " names joint " + fmt(j) + ", but " +
             skin_at + " has " + std::to_string(joints->size()) + " joints");
      const Mat4& jm = (*joints)[std::size_t(j)];
      for (std::size_t e = 0; e < 16; ++e) m[e] += w[std::size_t(k)] / sum * jm[e];
    }
    return m;
  };
  const double det = determinant3(world);
  // The NORMAL accessor, checked; a fault of it is reported after the vertices' own, as
  // when normals were read after positions.
  std::optional<Accessor> nrm;
  std::exception_ptr normal_error;
  if (const int n_index = attribute("NORMAL"); n_index >= 0) {
    try {
      nrm = accessor(n_index, at + " NORMAL",
                     {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
                      TINYGLTF_COMPONENT_TYPE_SHORT},
                     3);
      if (nrm->component_type != TINYGLTF_COMPONENT_TYPE_FLOAT && !nrm->normalized)
        fail(at + ": NORMAL accessor " + std::to_string(n_index) +
             ": integer normals must be normalized");
      if (nrm->count != pos.count)
        fail(at + ": NORMAL has " + std::to_string(nrm->count) + " elements, POSITION " +
             std::to_string(pos.count));
    } catch (const Error&) {
      normal_error = std::current_exception();
      nrm.reset();
    }
  }

  // Each vertex's position and normal (cofactor · sign(det) is the inverse transpose times
  // |det|, which normalizing removes), and for a skinned primitive whether its matrix
  // mirrors (a negative determinant).
  Mesh mesh;
  mesh.name = fs::path(path_).filename().string() + ":" + at;
  mesh.positions.resize(pos.count);
  if (nrm) mesh.normals.resize(pos.count);
  std::vector<char> mirrored(joints ? pos.count : 0, 0);
  std::vector<char> zero_normal(nrm ? pos.count : 0, 0);
  const Mat4 normal_matrix = cofactor(world);
  for_each_index(pos.count, [&](std::size_t i) {
    const Mat4 m = vertex_matrix(i);
    const bool mirror = joints ? determinant3(m) < 0 : det < 0;
    if (joints) mirrored[i] = mirror;
    const Vec3d p = transform_point(m, morphed(pos, &Morph::position, i));
    if (!fits_float(p))
      fail(at + ": POSITION " + std::to_string(i) + " is not a finite float (" +
           fmt(pos.get(i, 0)) + " " + fmt(pos.get(i, 1)) + " " + fmt(pos.get(i, 2)) +
           " in the world: " + fmt(p.x) + " " + fmt(p.y) + " " + fmt(p.z) + ")");
    mesh.positions[i] = to_vec4(p);
    if (!nrm) return;
    const double sign = mirror ? -1.0 : 1.0;
    Vec3d n = transform_vector(joints ? cofactor(m) : normal_matrix, morphed(*nrm, &Morph::normal, i));
    n = normalized({n.x * sign, n.y * sign, n.z * sign});
    if (finite3(n))
      mesh.normals[i] = to_vec4(n);
    else
      zero_normal[i] = 1;
  });
  if (normal_error) std::rethrow_exception(normal_error);
  if (std::find(zero_normal.begin(), zero_normal.end(), 1) != zero_normal.end()) {
    // a zero normal, or a singular transform: flat shading
    mesh.normals.clear();
    warn_once("normals", at + ": a zero or non-finite normal; the primitive is shaded flat");
  }
  if (const int t_index = attribute("TEXCOORD_0"); t_index >= 0) {
    Accessor uv = accessor(t_index, at + " TEXCOORD_0",
                           {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
                            TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT,
                            TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                           2);
    if (uv.count != pos.count)
      fail(at + ": TEXCOORD_0 has " + std::to_string(uv.count) + " elements, POSITION " +
           std::to_string(pos.count));
    // Core glTF's integer texture coordinates are normalized (3.7.2.1), whatever the flag
    // says; KHR_mesh_quantization's may be either, as declared.
    if (!quantized_) uv.normalized = true;
    mesh.texcoords.reserve(uv.count);
    const std::array<double, 6>& t = uv_transform.m;
    for (std::size_t i = 0; i < uv.count; ++i) {
      const double u0 = uv.get(i, 0), v0 = uv.get(i, 1);
      const float u = float(t[0] * u0 + t[1] * v0 + t[2]), v = float(t[3] * u0 + t[4] * v0 + t[5]);
      if (!std::isfinite(u) || !std::isfinite(v))
        fail(at + ": TEXCOORD_0 " + std::to_string(i) + " is not finite");
      mesh.texcoords.push_back({u, 1.0f - v});  // glTF's image row 0 is v = 0; rt2's v = 1
    }
  }

  // Corner indices: the indices accessor, or 0, 1, 2, ... without one.
  std::vector<std::uint32_t> corners;
  if (prim.indices >= 0) {
    const Accessor idx =
        accessor(prim.indices, at + " indices",
                 {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                  TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
                 1);
    corners.resize(idx.count);
    for_each_index(idx.count, [&](std::size_t i) {
      const double v = idx.get(i, 0);
      if (!(v < double(pos.count)))
        fail(at + ": index " + std::to_string(i) + " is " + fmt(v) + ", but there are only " +
             std::to_string(pos.count) + " vertices");
      corners[i] = std::uint32_t(v);
    });
  } else {
    corners.resize(pos.count);
    for (std::size_t i = 0; i < pos.count; ++i) corners[i] = std::uint32_t(i);
  }
  const std::size_t n_corners = corners.size();
  triangles_ += mode == TINYGLTF_MODE_TRIANGLES ? n_corners / 3 : n_corners > 2 ? n_corners - 2 : 0;
  if (triangles_ * kBytesPerTriangle > memory_)
    fail("its mesh instances hold " + std::to_string(triangles_) + " triangles or more, which need "
         "about " + memory_size(triangles_ * kBytesPerTriangle) + "; " + memory_size(memory_) +
         " of memory is available");
  if (mode == TINYGLTF_MODE_TRIANGLES && n_corners % 3 != 0)
    warn_once("leftover", at + ": " + std::to_string(n_corners) +
                              " corners is not a multiple of 3; the last are ignored");
  mesh.faces.resize(mode == TINYGLTF_MODE_TRIANGLES ? n_corners / 3
                    : n_corners > 2                 ? n_corners - 2
                                                    : 0);
  for_each_index(mesh.faces.size(), [&](std::size_t k) {
    // Face k of a list, a strip (every other one turned to keep the winding) or a fan.
    std::uint32_t a, b, c;
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      a = corners[3 * k], b = corners[3 * k + 1], c = corners[3 * k + 2];
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      a = corners[k + (k % 2)], b = corners[k + 1 - (k % 2)], c = corners[k + 2];
    } else {
      a = corners[0], b = corners[k + 1], c = corners[k + 2];
    }
    // A mirroring transform (det < 0) turns the winding; glTF says to turn it back. A skinned
    // triangle is turned back when two or three of its corners' matrices mirror.
    if (joints ? mirrored[a] + mirrored[b] + mirrored[c] >= 2 : det < 0) std::swap(b, c);
    mesh.faces[k] = {a, b, c};
  });
  mesh.face_materials.assign(mesh.faces.size(), scene_material);
  scene_.degenerate_triangles += mesh.drop_degenerate();
  if (into)
    into->append(mesh);
  else if (!mesh.faces.empty())
    scene_.meshes.push_back(std::move(mesh));
}

void GltfReader::set_camera(int node, int camera_index, const Mat4& world) {
  const std::string at = "node " + named(node, model_.nodes[std::size_t(node)].name);
  if (std::size_t(camera_index) >= model_.cameras.size())
    fail(at + ": camera " + std::to_string(camera_index) + " does not exist (" +
         std::to_string(model_.cameras.size()) + " cameras)");
  const tinygltf::Camera& c = model_.cameras[std::size_t(camera_index)];
  double fov = 60.0;
  if (c.type == "perspective") {
    fov = c.perspective.yfov * 180.0 / 3.14159265358979323846;
    if (!(fov > 0 && fov < 180))
      fail("camera " + named(camera_index, c.name) + ": yfov " + fmt(c.perspective.yfov) +
           " is not in (0, pi)");
  } else {
    warn_once("ortho", "camera " + named(camera_index, c.name) + " is " + one_line(c.type) +
                           "; rendered as a perspective camera of 60 degrees");
  }
  const Vec3d pos = transform_point(world, {0, 0, 0});
  const Vec3d dir = normalized(transform_vector(world, {0, 0, -1}));
  const Vec3d up = normalized(transform_vector(world, {0, 1, 0}));
  if (!finite3(pos) || !finite3(dir) || !finite3(up) || !fits_float(pos))
    fail(at + ": its transform gives the camera no position, direction or up");
  const vec4 d = to_vec4(dir), u = to_vec4(up);
  const vec4 side = cross(d, u);
  if (!(float(dot(side, side)) > 1e-12f)) fail(at + ": the camera's direction and up are parallel");
  scene_.camera = Camera(to_vec4(pos), d, u, float(fov));
  have_camera_ = true;
}

void GltfReader::add_light(int node, const tinygltf::Value& ext, const Mat4& world) {
  if (!ext.IsObject() || !ext.Has("light")) return;
  const tinygltf::Value& v = ext.Get("light");
  const std::string at = "node " + named(node, model_.nodes[std::size_t(node)].name);
  const int index = v.IsInt() ? v.Get<int>() : -1;
  if (index < 0 || std::size_t(index) >= model_.lights.size())
    fail(at + ": KHR_lights_punctual light " + (v.IsInt() ? std::to_string(index) : "?") +
         " does not exist (" + std::to_string(model_.lights.size()) + " lights)");
  const Vec3d pos = transform_point(world, {0, 0, 0});
  const Vec3d dir = normalized(transform_vector(world, {0, 0, -1}));
  if (!fits_float(pos)) fail(at + ": the light's position is not finite");
  if (lights_.size() >= kMaxGltfLights)
    fail("more than " + std::to_string(kMaxGltfLights) +
         " light instances (lights of nodes shared by many parents?); a scene of many lights "
         "is a TOML scene's [light_field]");
  lights_.push_back({index, pos, dir});
}

// Lights, once the scene's extent is known. glTF gives point and spot lights in candela
// (lm/sr) with inverse-square falloff, directional lights in lux (lm/m²); rt2's lights have
// no falloff (rt2/scene/light.h). A point light gets the intensity that gives, everywhere, the
// illuminance the glTF light gives at the scene's centre: I / d², d the distance from the
// light to the centre of the scene's bounds (at least R, half their diagonal, so that a light
// inside the scene does not blow up). A directional light becomes a point light 1000 R away
// against its direction, with its lux as intensity.
void GltfReader::finish_lights(const Framing& frame) {
  for (const PendingLight& p : lights_) {
    const tinygltf::Light& g = model_.lights[std::size_t(p.index)];
    const std::string at = "light " + named(p.index, g.name);
    Light l;
    if (!g.color.empty()) {
      if (g.color.size() != 3)
        fail(at + ": color has " + std::to_string(g.color.size()) + " numbers, expected 3");
      for (const double c : g.color)
        if (!(c >= 0 && c <= 1e6)) fail(at + ": color holds " + fmt(c) + ", expected >= 0");
      l.color = vec4(float(g.color[0]), float(g.color[1]), float(g.color[2]));
    }
    if (!(g.intensity >= 0 && g.intensity <= 1e30)) fail(at + ": intensity is " + fmt(g.intensity));
    if (!(g.range >= 0 && std::isfinite(g.range))) fail(at + ": range is " + fmt(g.range));
    if (g.type == "directional") {
      if (!finite3(p.direction)) fail(at + ": its node gives it no direction");
      warn_once("directional", at + " is directional; placed as a point light far away");
      const float far = 1000.0f * frame.radius;
      l.position = frame.center - to_vec4(p.direction) * far;
      l.intensity = float(g.intensity);
    } else {
      if (g.type == "spot")
        warn_once("spot", at + " is a spot light; rendered as a point light");
      else if (g.type != "point")
        fail(at + ": unknown type '" + one_line(g.type) + "'");
      l.position = to_vec4(p.position);
      const vec4 to_center = frame.center - l.position;
      const float d = std::max(std::sqrt(float(dot(to_center, to_center))), frame.radius);
      l.intensity = float(g.intensity / (double(d) * d));
      if (g.range > 0) l.range = float(g.range);
    }
    scene_.lights.push_back(l);
  }
}

// The framing of the scene's bounds (a framed camera, the lights' intensities, the
// framing light). Those of the file's own node transforms when it is posed by an
// animation: what a pose frames must not move from one time to the next.
Framing GltfReader::still_framing() {
  if (scene_.animation < 0) return framing_of(path_, scene_.bounds(), "scene");
  if (!file_.still) {
    const WarningsOff quiet;  // this reading's warnings were the first one's
    file_.still = GltfReader(file_, path_, scene_.assets, pose_, false).read().bounds();
  }
  // unposed, the file may have nothing to frame (every triangle degenerate ...): this pose's
  return framing_of(path_, file_.still->is_empty() ? scene_.bounds() : *file_.still, "scene");
}

Scene GltfReader::read() {
  if (!model_.asset.version.starts_with("2."))
    fail("asset.version is '" + one_line(model_.asset.version) + "'; rt2 reads glTF 2.0 only");
  on_path_.assign(model_.nodes.size(), 0);
  std::vector<int> roots;
  if (!model_.scenes.empty()) {
    const int s = model_.defaultScene >= 0 ? model_.defaultScene : 0;
    if (std::size_t(s) >= model_.scenes.size())
      fail("scene " + std::to_string(s) + " does not exist (" +
           std::to_string(model_.scenes.size()) + " scenes)");
    roots = model_.scenes[std::size_t(s)].nodes;
  } else {  // no scenes: every node that is no node's child
    std::vector<char> child(model_.nodes.size(), 0);
    for (const tinygltf::Node& n : model_.nodes)
      for (const int c : n.children)
        if (c >= 0 && std::size_t(c) < child.size()) child[std::size_t(c)] = 1;
    for (std::size_t i = 0; i < child.size(); ++i)
      if (!child[i]) roots.push_back(int(i));
  }
  pose_nodes();
  read_skins();
  for (const int r : roots) walk(r, kIdentity);
  place_meshes();
  const bool empty = scene_.meshes.empty() && scene_.instances.empty();
  if (!animate_ && empty) return std::move(scene_);  // still_framing's reading
  if (empty)
    fail(scene_.degenerate_triangles
             ? "all " + std::to_string(scene_.degenerate_triangles) + " triangles are degenerate"
             : "no triangles in the scene");
  const Framing frame = still_framing();
  if (!have_camera_) frame_camera(scene_, frame);
  finish_lights(frame);
  if (scene_.lights.empty()) scene_.lights.push_back(framing_light(frame));
  validate(path_, scene_);
  return std::move(scene_);
}

}  // namespace

std::shared_ptr<ParsedGltf> parse_gltf(const std::string& path, const AssetPolicy& policy) {
  auto file = std::make_shared<ParsedGltf>();
  parse_model(path, policy, file->model, file->quantized);
  return file;
}

Scene read_gltf_scene(ParsedGltf& file, const std::string& path, const AssetPolicy& policy,
                      const ScenePose& pose) {
  return GltfReader(file, path, policy, pose).read();
}

Scene read_gltf_scene(const std::string& path, const AssetPolicy& policy, const ScenePose& pose) {
  return read_gltf_scene(*parse_gltf(path, policy), path, policy, pose);
}

}  // namespace rt2::io
