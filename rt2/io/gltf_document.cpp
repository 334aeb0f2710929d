// rt2/io/gltf_document.cpp — a glTF file checked and taken apart before tinygltf reads it
// (rt2/io/gltf_document.h). The schema checks follow the glTF 2.0 JSON schema and those of
// the extensions rt2 reads, for every property rt2 or tinygltf reads: a wrong type, a value
// out of range or an array of the wrong length is an error naming its JSON path, never a
// default.
#include "rt2/io/gltf_document.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <set>
#include <string>
#include <string_view>

#include "rt2/io/gltf_scene.h"
#include "rt2/io/text.h"

namespace rt2::io {
namespace {

using nlohmann::json;

constexpr std::uint32_t kGlbMagic = 0x46546C67;                               // "glTF"
constexpr std::uint32_t kChunkJson = 0x4E4F534A;                              // "JSON"
constexpr std::uint32_t kChunkBin = 0x004E4942;                               // "BIN\0"
constexpr std::int64_t kMaxIndex = std::numeric_limits<std::int32_t>::max();  // tinygltf's int
constexpr std::int64_t kMaxBytes = std::int64_t(1) << 53;  // exact in a JSON number

// Extensions rt2 knows and does not use: a warning says what is lost.
struct Ignored {
  const char* name;
  const char* what;
};
constexpr Ignored kIgnoredExtensions[] = {
    {"KHR_materials_clearcoat", "clearcoat layers are not drawn"},
    {"KHR_materials_sheen", "sheen is not drawn"},
    {"KHR_materials_specular", "the specular strength and colour are not applied"},
    {"KHR_materials_volume", "volume attenuation is not applied"},
    {"KHR_materials_iridescence", "iridescence is not drawn"},
    {"KHR_materials_anisotropy", "anisotropy is not drawn"},
    {"KHR_materials_unlit", "unlit materials are shaded"},
    {"KHR_materials_variants", "only the default material of each primitive is used"},
    {"KHR_texture_basisu", "KTX2 textures are not read"},
    {"EXT_texture_webp", "WebP textures are read only where a fallback image exists"},
    {"EXT_mesh_gpu_instancing", "instanced copies are not drawn"},
    {"KHR_animation_pointer", "animated properties other than node transforms stay still"},
};

std::uint32_t le32(const std::string& b, std::size_t at) {
  std::uint32_t v;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}

// The JSON's nesting and number of values, before any parser sees it.
void check_json_shape(const std::string& path, std::string_view text) {
  int depth = 0;
  std::size_t values = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
      continue;
    }
    switch (c) {
      case '"':
        in_string = true;
        ++values;
        break;
      case '[':
      case '{':
        ++values;
        if (++depth > kMaxJsonDepth)
          error_at(path, 0, 0,
                   "JSON nests arrays and objects more than " + std::to_string(kMaxJsonDepth) +
                       " deep (at byte " + std::to_string(i) + ")");
        break;
      case ']':
      case '}':
        --depth;
        break;
      case ',':
        ++values;
        break;
      default:
        break;
    }
    if (values > kMaxJsonValues)
      error_at(path, 0, 0, "JSON holds more than " + std::to_string(kMaxJsonValues) + " values");
  }
}

// What a JSON value is, for messages.
const char* kind(const json& v) {
  switch (v.type()) {
    case json::value_t::object:
      return "an object";
    case json::value_t::array:
      return "an array";
    case json::value_t::string:
      return "a string";
    case json::value_t::boolean:
      return "true or false";
    case json::value_t::null:
      return "null";
    default:
      return "a number";
  }
}

// The schema checks: every function takes a value and its JSON path ("materials[0].name").
class Schema {
 public:
  explicit Schema(const std::string& file) : file_(file) {}

  [[noreturn]] void fail(const std::string& at, const std::string& msg) const {
    error_at(file_, 0, 0, at + " " + msg);
  }

  static const json* member(const json& o, const char* key) {
    const auto it = o.find(key);
    return it == o.end() ? nullptr : &*it;
  }
  const json& required(const json& o, const char* key, const std::string& at) const {
    const json* v = member(o, key);
    if (!v) fail(at, std::string("has no '") + key + "', which glTF requires");
    return *v;
  }
  const json& object(const json& v, const std::string& at) const {
    if (!v.is_object()) fail(at, std::string("is ") + kind(v) + ", expected an object");
    return v;
  }
  const json& array(const json& v, const std::string& at, std::size_t lo = 0,
                    std::size_t hi = std::size_t(-1)) const {
    if (!v.is_array()) fail(at, std::string("is ") + kind(v) + ", expected an array");
    if (v.size() < lo || v.size() > hi)
      fail(at,
           "has " + std::to_string(v.size()) + " elements, expected " +
               (lo == hi ? std::to_string(lo)
                         : std::to_string(lo) +
                               (hi == std::size_t(-1) ? " or more" : " to " + std::to_string(hi))));
    return v;
  }
  double number(const json& v, const std::string& at, double lo = -HUGE_VAL, double hi = HUGE_VAL,
                bool open_lo = false) const {
    if (!v.is_number()) fail(at, std::string("is ") + kind(v) + ", expected a number");
    const double x = v.get<double>();
    if (!std::isfinite(x)) fail(at, "is not a finite number");
    if (x < lo || x > hi || (open_lo && x == lo))
      fail(at, "is " + fmt(x) + ", expected " + range(lo, hi, open_lo));
    return x;
  }
  std::int64_t integer(const json& v, const std::string& at, std::int64_t lo = 0,
                       std::int64_t hi = kMaxIndex) const {
    const double x = v.is_number() ? v.get<double>() : 0.0;
    if (!v.is_number() || !(x == std::floor(x)))
      fail(at, std::string("is ") + (v.is_number() ? "not a whole number" : kind(v)) +
                   ", expected an integer");
    if (x < double(lo) || x > double(hi))
      fail(at, "is " + fmt(x) + ", expected " + range(double(lo), double(hi), false));
    return v.is_number_unsigned()  ? std::int64_t(v.get<std::uint64_t>())
           : v.is_number_integer() ? v.get<std::int64_t>()
                                   : std::int64_t(x);
  }
  std::int64_t one_of(const json& v, const std::string& at,
                      std::initializer_list<std::int64_t> allowed) const {
    const std::int64_t x = integer(v, at, std::numeric_limits<std::int32_t>::min());
    if (std::find(allowed.begin(), allowed.end(), x) == allowed.end()) {
      std::string list;
      for (const std::int64_t a : allowed) list += (list.empty() ? "" : ", ") + std::to_string(a);
      fail(at, "is " + std::to_string(x) + ", expected one of " + list);
    }
    return x;
  }
  const std::string& string(const json& v, const std::string& at) const {
    if (!v.is_string()) fail(at, std::string("is ") + kind(v) + ", expected a string");
    return v.get_ref<const std::string&>();
  }
  const std::string& one_of(const json& v, const std::string& at,
                            std::initializer_list<const char*> allowed) const {
    const std::string& s = string(v, at);
    for (const char* a : allowed)
      if (s == a) return s;
    std::string list;
    for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
    fail(at, "is '" + one_line(s) + "', expected one of " + list);
  }
  void boolean(const json& v, const std::string& at) const {
    if (!v.is_boolean()) fail(at, std::string("is ") + kind(v) + ", expected true or false");
  }
  void numbers(const json& v, const std::string& at, std::size_t lo, std::size_t hi,
               double min = -HUGE_VAL, double max = HUGE_VAL) const {
    array(v, at, lo, hi);
    for (std::size_t i = 0; i < v.size(); ++i)
      number(v[i], at + "[" + std::to_string(i) + "]", min, max);
  }
  void indices(const json& v, const std::string& at, std::size_t lo = 0) const {
    array(v, at, lo);
    std::set<std::int64_t> seen;
    for (std::size_t i = 0; i < v.size(); ++i)
      if (!seen.insert(integer(v[i], at + "[" + std::to_string(i) + "]")).second)
        fail(at, "names " + std::to_string(integer(v[i], at)) + " twice");
  }

  // Calls f(value, path) for member `key` of `o` when it is there.
  template <class F>
  void optional(const json& o, const char* key, const std::string& at, F&& f) const {
    if (const json* v = member(o, key)) f(*v, join(at, key));
  }
  // Calls f(element, path) for each object of the array `key` of `o`.
  template <class F>
  void each_object(const json& o, const char* key, const std::string& at, F&& f) const {
    optional(o, key, at, [&](const json& a, const std::string& a_at) {
      array(a, a_at);
      for (std::size_t i = 0; i < a.size(); ++i) {
        const std::string e_at = a_at + "[" + std::to_string(i) + "]";
        f(object(a[i], e_at), e_at);
      }
    });
  }
  // The object of extension `name` of `o`, or null.
  const json* extension(const json& o, const char* name, const std::string& at) const {
    const json* exts = member(o, "extensions");
    if (!exts) return nullptr;
    object(*exts, join(at, "extensions"));
    const json* e = member(*exts, name);
    return e ? &object(*e, join(join(at, "extensions"), name)) : nullptr;
  }

  static std::string join(const std::string& at, const char* key) {
    return at.empty() ? key : at + "." + key;
  }

 private:
  static std::string range(double lo, double hi, bool open_lo) {
    if (hi == HUGE_VAL || hi >= double(kMaxBytes)) return (open_lo ? "> " : ">= ") + fmt(lo);
    return fmt(lo) + (open_lo ? " (exclusive)" : "") + " to " + fmt(hi);
  }
  const std::string& file_;
};

// ---- the glTF 2.0 schema, as far as rt2 and tinygltf read it ---------------------------------

void check_texture_info(const Schema& s, const json& t, const std::string& at) {
  s.object(t, at);
  s.integer(s.required(t, "index", at), Schema::join(at, "index"));
  s.optional(t, "texCoord", at, [&](const json& v, const std::string& p) { s.integer(v, p); });
  s.optional(t, "scale", at, [&](const json& v, const std::string& p) { s.number(v, p); });
  s.optional(t, "strength", at, [&](const json& v, const std::string& p) { s.number(v, p, 0, 1); });
  if (const json* x = s.extension(t, "KHR_texture_transform", at)) {
    const std::string x_at = at + ".extensions.KHR_texture_transform";
    s.optional(*x, "offset", x_at,
               [&](const json& v, const std::string& p) { s.numbers(v, p, 2, 2); });
    s.optional(*x, "rotation", x_at, [&](const json& v, const std::string& p) { s.number(v, p); });
    s.optional(*x, "scale", x_at,
               [&](const json& v, const std::string& p) { s.numbers(v, p, 2, 2); });
    s.optional(*x, "texCoord", x_at, [&](const json& v, const std::string& p) { s.integer(v, p); });
  }
}

void check_material(const Schema& s, const json& m, const std::string& at) {
  const auto tex = [&](const json& v, const std::string& p) { check_texture_info(s, v, p); };
  s.optional(m, "name", at, [&](const json& v, const std::string& p) { s.string(v, p); });
  s.optional(m, "pbrMetallicRoughness", at, [&](const json& pbr, const std::string& p) {
    s.object(pbr, p);
    s.optional(pbr, "baseColorFactor", p,
               [&](const json& v, const std::string& q) { s.numbers(v, q, 4, 4, 0, 1); });
    s.optional(pbr, "metallicFactor", p,
               [&](const json& v, const std::string& q) { s.number(v, q, 0, 1); });
    s.optional(pbr, "roughnessFactor", p,
               [&](const json& v, const std::string& q) { s.number(v, q, 0, 1); });
    s.optional(pbr, "baseColorTexture", p, tex);
    s.optional(pbr, "metallicRoughnessTexture", p, tex);
  });
  s.optional(m, "normalTexture", at, tex);
  s.optional(m, "occlusionTexture", at, tex);
  s.optional(m, "emissiveTexture", at, tex);
  s.optional(m, "emissiveFactor", at,
             [&](const json& v, const std::string& p) { s.numbers(v, p, 3, 3, 0, 1); });
  s.optional(m, "alphaMode", at, [&](const json& v, const std::string& p) {
    s.one_of(v, p, {"OPAQUE", "MASK", "BLEND"});
  });
  s.optional(m, "alphaCutoff", at, [&](const json& v, const std::string& p) { s.number(v, p, 0); });
  s.optional(m, "doubleSided", at, [&](const json& v, const std::string& p) { s.boolean(v, p); });
  const std::string x_at = at + ".extensions.";
  if (const json* x = s.extension(m, "KHR_materials_emissive_strength", at))
    s.optional(*x, "emissiveStrength", x_at + "KHR_materials_emissive_strength",
               [&](const json& v, const std::string& p) { s.number(v, p, 0); });
  if (const json* x = s.extension(m, "KHR_materials_ior", at))
    s.optional(*x, "ior", x_at + "KHR_materials_ior",
               [&](const json& v, const std::string& p) { s.number(v, p, 0); });
  if (const json* x = s.extension(m, "KHR_materials_transmission", at)) {
    const std::string p = x_at + "KHR_materials_transmission";
    s.optional(*x, "transmissionFactor", p,
               [&](const json& v, const std::string& q) { s.number(v, q, 0, 1); });
    s.optional(*x, "transmissionTexture", p, tex);
  }
  if (const json* x = s.extension(m, "KHR_materials_pbrSpecularGlossiness", at)) {
    const std::string p = x_at + "KHR_materials_pbrSpecularGlossiness";
    s.optional(*x, "diffuseFactor", p,
               [&](const json& v, const std::string& q) { s.numbers(v, q, 4, 4, 0, 1); });
    s.optional(*x, "specularFactor", p,
               [&](const json& v, const std::string& q) { s.numbers(v, q, 3, 3, 0, 1); });
    s.optional(*x, "glossinessFactor", p,
               [&](const json& v, const std::string& q) { s.number(v, q, 0, 1); });
    s.optional(*x, "diffuseTexture", p, tex);
    s.optional(*x, "specularGlossinessTexture", p, tex);
  }
}

void check_accessor(const Schema& s, const json& a, const std::string& at) {
  s.optional(a, "bufferView", at, [&](const json& v, const std::string& p) { s.integer(v, p); });
  s.optional(a, "byteOffset", at,
             [&](const json& v, const std::string& p) { s.integer(v, p, 0, kMaxBytes); });
  s.one_of(s.required(a, "componentType", at), at + ".componentType",
           {5120, 5121, 5122, 5123, 5125, 5126});
  s.optional(a, "normalized", at, [&](const json& v, const std::string& p) { s.boolean(v, p); });
  s.integer(s.required(a, "count", at), at + ".count", 1, kMaxBytes);
  s.one_of(s.required(a, "type", at), at + ".type",
           {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"});
  s.optional(a, "max", at, [&](const json& v, const std::string& p) { s.numbers(v, p, 1, 16); });
  s.optional(a, "min", at, [&](const json& v, const std::string& p) { s.numbers(v, p, 1, 16); });
  s.optional(a, "sparse", at, [&](const json& v, const std::string& p) {
    s.object(v, p);
    s.integer(s.required(v, "count", p), p + ".count", 1, kMaxBytes);
  });
}

void check_buffer_view(const Schema& s, const json& v, const std::string& at) {
  s.integer(s.required(v, "buffer", at), at + ".buffer");
  s.optional(v, "byteOffset", at,
             [&](const json& x, const std::string& p) { s.integer(x, p, 0, kMaxBytes); });
  s.integer(s.required(v, "byteLength", at), at + ".byteLength", 1, kMaxBytes);
  s.optional(v, "byteStride", at, [&](const json& x, const std::string& p) {
    if (s.integer(x, p, 4, 252) % 4 != 0)
      s.fail(p, "is " + std::to_string(s.integer(x, p)) + ", expected a multiple of 4");
  });
  s.optional(v, "target", at, [&](const json& x, const std::string& p) {
    s.one_of(x, p, {34962, 34963});
  });
  if (const json* m = s.extension(v, "EXT_meshopt_compression", at)) {
    const std::string p = at + ".extensions.EXT_meshopt_compression";
    s.integer(s.required(*m, "buffer", p), p + ".buffer");
    s.optional(*m, "byteOffset", p,
               [&](const json& x, const std::string& q) { s.integer(x, q, 0, kMaxBytes); });
    s.integer(s.required(*m, "byteLength", p), p + ".byteLength", 1, kMaxBytes);
    s.integer(s.required(*m, "byteStride", p), p + ".byteStride", 1, 256);
    s.integer(s.required(*m, "count", p), p + ".count", 1, kMaxBytes);
    s.one_of(s.required(*m, "mode", p), p + ".mode", {"ATTRIBUTES", "TRIANGLES", "INDICES"});
    s.optional(*m, "filter", p, [&](const json& x, const std::string& q) {
      s.one_of(x, q, {"NONE", "OCTAHEDRAL", "QUATERNION", "EXPONENTIAL"});
    });
  }
}

void check_mesh(const Schema& s, const json& m, const std::string& at) {
  s.optional(m, "name", at, [&](const json& v, const std::string& p) { s.string(v, p); });
  s.array(s.required(m, "primitives", at), at + ".primitives", 1);
  s.each_object(m, "primitives", at, [&](const json& prim, const std::string& p) {
    s.object(s.required(prim, "attributes", p), p + ".attributes");
    for (const auto& [name, index] : prim["attributes"].items())
      s.integer(index, p + ".attributes." + one_line(name));
    s.optional(prim, "indices", p, [&](const json& v, const std::string& q) { s.integer(v, q); });
    s.optional(prim, "material", p, [&](const json& v, const std::string& q) { s.integer(v, q); });
    s.optional(prim, "mode", p,
               [&](const json& v, const std::string& q) { s.integer(v, q, 0, 6); });
    s.each_object(prim, "targets", p, [&](const json& t, const std::string& q) {
      for (const auto& [name, index] : t.items()) s.integer(index, q + "." + one_line(name));
    });
    if (const json* d = s.extension(prim, "KHR_draco_mesh_compression", p)) {
      const std::string q = p + ".extensions.KHR_draco_mesh_compression";
      s.integer(s.required(*d, "bufferView", q), q + ".bufferView");
      s.object(s.required(*d, "attributes", q), q + ".attributes");
      for (const auto& [name, id] : (*d)["attributes"].items())
        s.integer(id, q + ".attributes." + one_line(name));
    }
  });
  s.optional(m, "weights", at,
             [&](const json& v, const std::string& p) { s.numbers(v, p, 0, std::size_t(-1)); });
}

void check_node(const Schema& s, const json& n, const std::string& at) {
  const auto index = [&](const json& v, const std::string& p) { s.integer(v, p); };
  s.optional(n, "name", at, [&](const json& v, const std::string& p) { s.string(v, p); });
  s.optional(n, "camera", at, index);
  s.optional(n, "mesh", at, index);
  s.optional(n, "skin", at, index);
  s.optional(n, "children", at, [&](const json& v, const std::string& p) { s.indices(v, p); });
  s.optional(n, "matrix", at,
             [&](const json& v, const std::string& p) { s.numbers(v, p, 16, 16); });
  s.optional(n, "rotation", at,
             [&](const json& v, const std::string& p) { s.numbers(v, p, 4, 4, -1, 1); });
  s.optional(n, "scale", at, [&](const json& v, const std::string& p) { s.numbers(v, p, 3, 3); });
  s.optional(n, "translation", at,
             [&](const json& v, const std::string& p) { s.numbers(v, p, 3, 3); });
  s.optional(n, "weights", at,
             [&](const json& v, const std::string& p) { s.numbers(v, p, 0, std::size_t(-1)); });
  if (const json* l = s.extension(n, "KHR_lights_punctual", at))
    s.integer(s.required(*l, "light", at + ".extensions.KHR_lights_punctual"),
              at + ".extensions.KHR_lights_punctual.light");
}

void check_skin(const Schema& s, const json& k, const std::string& at) {
  const auto index = [&](const json& v, const std::string& p) { s.integer(v, p); };
  s.optional(k, "name", at, [&](const json& v, const std::string& p) { s.string(v, p); });
  s.optional(k, "inverseBindMatrices", at, index);
  s.optional(k, "skeleton", at, index);  // not used: the joints' world matrices place a skin
  const json& joints = s.required(k, "joints", at);
  s.array(joints, at + ".joints", 1, kMaxGltfJoints);
  s.indices(joints, at + ".joints");
}

void check_animation(const Schema& s, const json& a, const std::string& at) {
  const auto index = [&](const json& v, const std::string& p) { s.integer(v, p); };
  s.optional(a, "name", at, [&](const json& v, const std::string& p) { s.string(v, p); });
  s.array(s.required(a, "channels", at), at + ".channels", 1);
  s.array(s.required(a, "samplers", at), at + ".samplers", 1);
  s.each_object(a, "channels", at, [&](const json& c, const std::string& p) {
    s.integer(s.required(c, "sampler", p), p + ".sampler");
    const json& target = s.object(s.required(c, "target", p), p + ".target");
    s.optional(target, "node", p + ".target", index);
    s.one_of(s.required(target, "path", p + ".target"), p + ".target.path",
             {"translation", "rotation", "scale", "weights", "pointer"});
  });
  s.each_object(a, "samplers", at, [&](const json& v, const std::string& p) {
    s.integer(s.required(v, "input", p), p + ".input");
    s.integer(s.required(v, "output", p), p + ".output");
    s.optional(v, "interpolation", p, [&](const json& i, const std::string& q) {
      s.one_of(i, q, {"LINEAR", "STEP", "CUBICSPLINE"});
    });
  });
}

void check_camera(const Schema& s, const json& c, const std::string& at) {
  s.optional(c, "name", at, [&](const json& v, const std::string& p) { s.string(v, p); });
  const std::string& type =
      s.one_of(s.required(c, "type", at), at + ".type", {"perspective", "orthographic"});
  const std::string p = at + "." + type;
  const json& o = s.object(s.required(c, type.c_str(), at), p);
  const auto positive = [&](const json& v, const std::string& q) {
    s.number(v, q, 0, HUGE_VAL, true);
  };
  if (type == "perspective") {
    s.number(s.required(o, "yfov", p), p + ".yfov", 0, HUGE_VAL, true);
    s.number(s.required(o, "znear", p), p + ".znear", 0, HUGE_VAL, true);
    s.optional(o, "zfar", p, positive);
    s.optional(o, "aspectRatio", p, positive);
  } else {
    s.number(s.required(o, "xmag", p), p + ".xmag");
    s.number(s.required(o, "ymag", p), p + ".ymag");
    s.number(s.required(o, "zfar", p), p + ".zfar", 0, HUGE_VAL, true);
    s.number(s.required(o, "znear", p), p + ".znear", 0);
  }
}

void check_light(const Schema& s, const json& l, const std::string& at) {
  s.optional(l, "name", at, [&](const json& v, const std::string& p) { s.string(v, p); });
  const std::string& type =
      s.one_of(s.required(l, "type", at), at + ".type", {"directional", "point", "spot"});
  s.optional(l, "color", at,
             [&](const json& v, const std::string& p) { s.numbers(v, p, 3, 3, 0, 1); });
  s.optional(l, "intensity", at, [&](const json& v, const std::string& p) { s.number(v, p, 0); });
  s.optional(l, "range", at,
             [&](const json& v, const std::string& p) { s.number(v, p, 0, HUGE_VAL, true); });
  if (type == "spot") {
    const json& spot = s.object(s.required(l, "spot", at), at + ".spot");
    s.optional(spot, "innerConeAngle", at + ".spot",
               [&](const json& v, const std::string& p) { s.number(v, p, 0, M_PI / 2); });
    s.optional(spot, "outerConeAngle", at + ".spot",
               [&](const json& v, const std::string& p) { s.number(v, p, 0, M_PI / 2, true); });
  }
}

// glTF 1.0 files keep their objects in dictionaries keyed by id, and say so in asset.version.
[[noreturn]] void refuse_gltf1(const std::string& path, const std::string& version) {
  error_at(path, 0, 0,
           "glTF 1.0 is not supported (asset.version " +
               (version.empty() ? std::string("absent, and its meshes are keyed by name")
                                : "'" + one_line(version) + "'") +
               "); rt2 reads glTF 2.0 (convert it, e.g. with Khronos' glTF-Pipeline)");
}

// asset.version, and extensionsUsed / extensionsRequired: refuses glTF 1.0 and extensions
// rt2 must have but lacks; warns once for each used extension it ignores.
void check_asset_and_extensions(const std::string& path, const Schema& s, const json& root) {
  const json* asset = Schema::member(root, "asset");
  if (!asset) {
    const json* meshes = Schema::member(root, "meshes");
    if (meshes && meshes->is_object()) refuse_gltf1(path, "");
    s.fail("the JSON", "has no 'asset', which glTF requires (is it a glTF file?)");
  }
  s.object(*asset, "asset");
  const std::string& version = s.string(s.required(*asset, "version", "asset"), "asset.version");
  if (version.starts_with("1") || version.starts_with("0")) refuse_gltf1(path, version);
  if (!version.starts_with("2."))
    s.fail("asset.version", "is '" + one_line(version) + "'; rt2 reads glTF 2.0");
  s.optional(*asset, "minVersion", "asset", [&](const json& v, const std::string& p) {
    if (s.string(v, p) != "2.0")
      s.fail(p, "is '" + one_line(v.get<std::string>()) + "'; rt2 reads glTF 2.0");
  });
  const auto names = [&](const char* key) {
    std::vector<std::string> out;
    s.optional(root, key, "", [&](const json& v, const std::string& p) {
      s.array(v, p);
      for (std::size_t i = 0; i < v.size(); ++i)
        out.push_back(s.string(v[i], p + "[" + std::to_string(i) + "]"));
    });
    return out;
  };
  const auto known = [](const std::string& name) {
    return std::any_of(std::begin(kGltfExtensions), std::end(kGltfExtensions),
                       [&](const char* e) { return name == e; });
  };
  for (const std::string& name : names("extensionsRequired"))
    if (!known(name))
      error_at(path, 0, 0,
               "requires extension " + one_line(name) +
                   " (extensionsRequired), which rt2 does not "
                   "implement");
  for (const std::string& name : names("extensionsUsed")) {
    if (known(name)) continue;
    const auto it = std::find_if(std::begin(kIgnoredExtensions), std::end(kIgnoredExtensions),
                                 [&](const Ignored& i) { return name == i.name; });
    warn(path + ": ignores extension " + one_line(name) +
         (it != std::end(kIgnoredExtensions) ? std::string(": ") + it->what : ""));
  }
}

// The schema of every top-level array rt2 or tinygltf reads.
// Fills `files` with each buffer's file uri ("" for none or a data: URI).
void check_schema(const Schema& s, const json& root, bool glb, std::vector<std::string>& files) {
  s.optional(root, "scene", "", [&](const json& v, const std::string& p) { s.integer(v, p); });
  s.each_object(root, "scenes", "", [&](const json& sc, const std::string& at) {
    s.optional(sc, "name", at, [&](const json& v, const std::string& p) { s.string(v, p); });
    s.optional(sc, "nodes", at, [&](const json& v, const std::string& p) { s.indices(v, p); });
  });
  s.each_object(root, "nodes", "",
                [&](const json& n, const std::string& at) { check_node(s, n, at); });
  s.each_object(root, "meshes", "",
                [&](const json& m, const std::string& at) { check_mesh(s, m, at); });
  s.each_object(root, "accessors", "",
                [&](const json& a, const std::string& at) { check_accessor(s, a, at); });
  s.each_object(root, "bufferViews", "",
                [&](const json& v, const std::string& at) { check_buffer_view(s, v, at); });
  std::size_t index = 0;
  s.each_object(root, "buffers", "", [&](const json& b, const std::string& at) {
    s.integer(s.required(b, "byteLength", at), at + ".byteLength", 1, kMaxBytes);
    bool fallback = false;
    if (const json* m = s.extension(b, "EXT_meshopt_compression", at))
      s.optional(*m, "fallback", at + ".extensions.EXT_meshopt_compression",
                 [&](const json& v, const std::string& p) {
                   s.boolean(v, p);
                   fallback = v.get<bool>();
                 });
    const json* uri = Schema::member(b, "uri");
    if (uri) s.string(*uri, at + ".uri");
    files.push_back(uri && !uri->get<std::string>().starts_with("data:") ? uri->get<std::string>()
                                                                         : "");
    if (!uri && !fallback && !(glb && index == 0))
      s.fail(at, glb ? "has no uri: only the first buffer of a GLB may use its BIN chunk"
                     : "has no uri, and only a GLB's first buffer may have none");
    ++index;
  });
  s.each_object(root, "images", "", [&](const json& img, const std::string& at) {
    const json* uri = Schema::member(img, "uri");
    const json* view = Schema::member(img, "bufferView");
    if (uri) s.string(*uri, at + ".uri");
    if (view) s.integer(*view, at + ".bufferView");
    if (!uri == !view) s.fail(at, "must have exactly one of uri and bufferView");
    s.optional(img, "mimeType", at, [&](const json& v, const std::string& p) { s.string(v, p); });
  });
  s.each_object(root, "textures", "", [&](const json& t, const std::string& at) {
    s.optional(t, "sampler", at, [&](const json& v, const std::string& p) { s.integer(v, p); });
    s.optional(t, "source", at, [&](const json& v, const std::string& p) { s.integer(v, p); });
  });
  s.each_object(root, "samplers", "", [&](const json& t, const std::string& at) {
    s.optional(t, "magFilter", at, [&](const json& v, const std::string& p) {
      s.one_of(v, p, {9728, 9729});
    });
    s.optional(t, "minFilter", at, [&](const json& v, const std::string& p) {
      s.one_of(v, p, {9728, 9729, 9984, 9985, 9986, 9987});
    });
    s.optional(t, "wrapS", at, [&](const json& v, const std::string& p) {
      s.one_of(v, p, {33071, 33648, 10497});
    });
    s.optional(t, "wrapT", at, [&](const json& v, const std::string& p) {
      s.one_of(v, p, {33071, 33648, 10497});
    });
  });
  s.each_object(root, "materials", "",
                [&](const json& m, const std::string& at) { check_material(s, m, at); });
  s.each_object(root, "cameras", "",
                [&](const json& c, const std::string& at) { check_camera(s, c, at); });
  s.each_object(root, "skins", "",
                [&](const json& k, const std::string& at) { check_skin(s, k, at); });
  s.each_object(root, "animations", "",
                [&](const json& a, const std::string& at) { check_animation(s, a, at); });
  if (const json* l = s.extension(root, "KHR_lights_punctual", ""))
    s.each_object(*l, "lights", "extensions.KHR_lights_punctual",
                  [&](const json& light, const std::string& at) { check_light(s, light, at); });
}

}  // namespace

GltfDocument read_gltf_document(const std::string& path, const std::string& bytes) {
  GltfDocument doc;
  std::string_view text = bytes;
  if (bytes.size() >= 4 && le32(bytes, 0) == kGlbMagic) {
    doc.glb = true;
    if (bytes.size() < 20)
      error_at(path, 0, 0, "GLB is truncated: " + std::to_string(bytes.size()) + " bytes");
    const std::uint32_t version = le32(bytes, 4), length = le32(bytes, 8);
    if (version == 1) refuse_gltf1(path, "1 (binary glTF version 1)");
    if (version != 2)
      error_at(path, 0, 0, "GLB version " + std::to_string(version) + "; rt2 reads version 2");
    if (length != bytes.size())
      error_at(path, 0, 0,
               "GLB header gives a length of " + std::to_string(length) + " bytes, the file has " +
                   std::to_string(bytes.size()));
    std::size_t at = 12;
    bool first = true;
    while (at < bytes.size()) {
      if (bytes.size() - at < 8)
        error_at(path, 0, 0, "GLB chunk header at byte " + std::to_string(at) + " is truncated");
      const std::uint32_t size = le32(bytes, at), type = le32(bytes, at + 4);
      if (size > bytes.size() - at - 8)
        error_at(path, 0, 0,
                 "GLB chunk at byte " + std::to_string(at) + " claims " + std::to_string(size) +
                     " bytes, beyond the file's end");
      const std::string_view data(bytes.data() + at + 8, size);
      if (first && type != kChunkJson) error_at(path, 0, 0, "GLB's first chunk is not its JSON");
      if (first)
        text = data;
      else if (type == kChunkBin && doc.bin.empty())
        doc.bin.assign(data);
      else if (type == kChunkJson || type == kChunkBin)
        error_at(path, 0, 0,
                 "GLB has a second " + std::string(type == kChunkJson ? "JSON" : "BIN") + " chunk");
      first = false;
      at += 8 + size;  // other chunk types are skipped, as glTF says
    }
  }
  if (text.empty()) error_at(path, 0, 0, "file is empty");
  check_json_shape(path, text);
  json root;
  try {
    root = json::parse(text.begin(), text.end());
  } catch (const json::exception& e) {
    error_at(path, 0, 0, std::string("is not valid JSON: ") + one_line(e.what()));
  }
  const Schema s(path);
  if (!root.is_object())
    s.fail("the JSON", std::string("is ") + kind(root) + ", expected an object");
  check_asset_and_extensions(path, s, root);
  check_schema(s, root, doc.glb, doc.buffer_files);
  if (const json* used = Schema::member(root, "extensionsUsed"))
    for (const json& name : *used) doc.quantized |= name == "KHR_mesh_quantization";

  // Rewrites for tinygltf: Draco primitives' indices (rt2 makes them) and meshopt fallback
  // buffers (which hold no data).
  bool rewritten = false;
  if (json* meshes = root.contains("meshes") ? &root["meshes"] : nullptr)
    for (std::size_t m = 0; m < meshes->size(); ++m) {
      json& prims = (*meshes)[m]["primitives"];
      for (std::size_t p = 0; p < prims.size(); ++p) {
        json& prim = prims[p];
        if (!prim.contains("extensions") ||
            !prim["extensions"].contains("KHR_draco_mesh_compression"))
          continue;
        const json& ext = prim["extensions"]["KHR_draco_mesh_compression"];
        DracoPrimitive d{int(m), int(p), -1, ext["bufferView"].get<int>(), {}};
        for (const auto& [name, id] : ext["attributes"].items())
          d.attributes.emplace_back(name, id.get<std::uint32_t>());
        if (prim.contains("indices")) {
          d.indices = prim["indices"].get<int>();
          prim.erase("indices");
          rewritten = true;
        }
        doc.draco.push_back(d);
      }
    }
  if (const json* views = Schema::member(root, "bufferViews"))
    for (std::size_t v = 0; v < views->size(); ++v) {
      const json& view = (*views)[v];
      const json* exts = Schema::member(view, "extensions");
      const json* m = exts ? Schema::member(*exts, "EXT_meshopt_compression") : nullptr;
      if (!m) continue;
      MeshoptView mv;
      mv.view = int(v);
      mv.buffer = (*m)["buffer"].get<int>();
      mv.offset = m->value("byteOffset", std::uint64_t(0));
      mv.length = (*m)["byteLength"].get<std::uint64_t>();
      mv.stride = (*m)["byteStride"].get<std::uint64_t>();
      mv.count = (*m)["count"].get<std::uint64_t>();
      mv.mode = (*m)["mode"].get<std::string>();
      mv.filter = m->value("filter", std::string("NONE"));
      doc.meshopt.push_back(mv);
    }
  if (json* buffers = root.contains("buffers") ? &root["buffers"] : nullptr)
    for (std::size_t b = 0; b < buffers->size(); ++b) {
      json& buffer = (*buffers)[b];
      const json* ext = buffer.contains("extensions")
                            ? Schema::member(buffer["extensions"], "EXT_meshopt_compression")
                            : nullptr;
      if (!ext || !ext->value("fallback", false)) continue;
      doc.fallback_buffers.push_back(int(b));
      buffer["uri"] = "data:application/octet-stream;base64,AA==";  // one byte: tinygltf wants data
      buffer["byteLength"] = 1;
      rewritten = true;
    }
  doc.json = rewritten ? root.dump() : std::string(text);
  return doc;
}

std::string tinygltf_bytes(const GltfDocument& doc) {
  if (!doc.glb) return doc.json;
  const auto put32 = [](std::string& out, std::uint32_t v) {
    out.append(reinterpret_cast<const char*>(&v), 4);
  };
  std::string json = doc.json;
  json.resize((json.size() + 3) / 4 * 4, ' ');
  std::string bin = doc.bin;
  bin.resize((bin.size() + 3) / 4 * 4, '\0');
  const std::size_t length = 12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size());
  std::string out;
  out.reserve(length);
  put32(out, kGlbMagic);
  put32(out, 2);
  put32(out, std::uint32_t(length));
  put32(out, std::uint32_t(json.size()));
  put32(out, kChunkJson);
  out += json;
  if (!bin.empty()) {
    put32(out, std::uint32_t(bin.size()));
    put32(out, kChunkBin);
    out += bin;
  }
  return out;
}

}  // namespace rt2::io
