// rt2/io/mtl.cpp — reading MTL text, checked line by line, and the MTL → Material mapping of
// scenes/FORMAT.md (internal; see rt2/io/mtl.h).
#include "rt2/io/mtl.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <span>
#include <vector>

#include "rt2/io/text.h"

namespace rt2::io {
namespace {

constexpr std::string_view kColorKeys[] = {"Ka", "Kd", "Ks", "Ke", "Kt", "Tf", "Kr"};
constexpr std::string_view kNumberKeys[] = {"Ns", "Ni", "d",  "Tr",  "sharpness", "Pr",
                                            "Pm", "Ps", "Pc", "Pcr", "aniso",     "anisor"};
constexpr std::string_view kTextureKeys[] = {"bump", "disp", "decal", "refl", "norm"};

template <std::size_t N>
bool one_of(std::string_view key, const std::string_view (&keys)[N]) {
  return std::find(std::begin(keys), std::end(keys), key) != std::end(keys);
}

bool is_texture(std::string_view key) {
  return key.starts_with("map_") || one_of(key, kTextureKeys);
}

float clamp01(float v) { return std::clamp(v, 0.0f, 1.0f); }

vec4 color(const float c[3]) { return vec4(clamp01(c[0]), clamp01(c[1]), clamp01(c[2])); }

// The statements of one MTL file, read in order.
class MtlReader {
 public:
  MtlReader(const std::string& file, MtlMaterials& wanted) : file_(file), wanted_(wanted) {}

  void line(std::size_t line, std::string_view s) {
    if (s.empty() || s.starts_with('#')) return;
    line_ = line;
    const std::vector<std::string_view> t = split_blanks(s);
    check_exponents(file_, line, t);  // as in an OBJ: none is a sensible number
    const std::string_view key = t[0];
    const std::span<const std::string_view> values = std::span(t).subspan(1);
    if (key == "newmtl") {
      start(after_keyword(s));
    } else if (one_of(key, kColorKeys)) {
      read_color(key, values);
    } else if (one_of(key, kNumberKeys)) {
      read_number(key, values);
    } else if (key == "illum") {
      read_illum(values);
    } else if (is_texture(key)) {
      if (key == "map_Kd" && current_) current_->diffuse_texture = true;
      if (current_ && read_texture(key, values)) return;
      if (current_ && !texture_line_) {
        texture_line_ = line;
        texture_key_ = key;
      }
    }
  }

  // The warnings, once per file.
  void finish() const {
    if (texture_line_)
      warn(location(file_, texture_line_, 0) + ": '" + std::string(texture_key_) +
           "' is not supported; it and the other unsupported texture statements of this file "
           "are ignored (rt2 reads map_Kd, map_Ke, map_Pr, map_Pm and norm)");
    if (spectral_line_)
      warn(location(file_, spectral_line_, 0) +
           ": spectral and CIE XYZ colours are not supported; those of this file are ignored");
  }

 private:
  void start(std::string_view name) {
    const auto it = wanted_.find(name);
    current_ = nullptr;
    name_ = name;
    if (it == wanted_.end() || it->second) return;  // not asked for, or defined before
    it->second.emplace();
    current_ = &*it->second;
    current_->file = file_;
  }

  [[noreturn]] void fail(const std::string& msg) const {
    error_at(file_, line_, 0,
             (name_ ? "material '" + std::string(*name_) + "': " : std::string()) + msg);
  }

  float number(std::string_view key, std::string_view token) const {
    double v = 0.0;
    if (!parse_double(token, v))
      fail(std::string(key) + " must be a number (got '" + std::string(token) + "')");
    if (!std::isfinite(v) || std::fabs(v) > FLT_MAX)
      fail(std::string(key) + " must be a finite number (got '" + std::string(token) + "')");
    return static_cast<float>(v);
  }

  // 1 number (grey: g = b = r, as the MTL specification says) or 3.
  void read_color(std::string_view key, std::span<const std::string_view> values) {
    if (!values.empty() && (values[0] == "spectral" || values[0] == "xyz")) {
      if (current_ && !spectral_line_) spectral_line_ = line_;
      return;
    }
    if (values.size() != 1 && values.size() != 3)
      fail(std::string(key) + " needs 1 or 3 numbers (got " + std::to_string(values.size()) + ")");
    float c[3];
    for (std::size_t i = 0; i < 3; ++i) c[i] = number(key, values[values.size() == 1 ? 0 : i]);
    if (!current_) return;
    MtlMaterial& m = *current_;
    if (key == "Ka") std::copy(c, c + 3, m.ka);
    if (key == "Kd") {
      std::copy(c, c + 3, m.kd);
      m.has_kd = true;
    }
    if (key == "Ks") std::copy(c, c + 3, m.ks);
    if (key == "Ke") std::copy(c, c + 3, m.ke);
    if (key == "Kr") {
      m.kr = std::max({c[0], c[1], c[2]});
      m.has_kr = true;
    }
  }

  void read_number(std::string_view key, std::span<const std::string_view> values) {
    if (key == "d" && !values.empty() && values[0] == "-halo") values = values.subspan(1);
    if (values.size() != 1)
      fail(std::string(key) + " needs 1 number (got " + std::to_string(values.size()) + ")");
    const float v = number(key, values[0]);
    if (!current_) return;
    MtlMaterial& m = *current_;
    if (key == "Ns") m.ns = v;
    if (key == "Ni") {
      m.ni = v;
      m.has_ni = true;
    }
    if (key == "d") {
      m.d = v;
      m.has_d = true;
    }
    if (key == "Tr") {
      m.tr = v;
      m.has_tr = true;
    }
    if (key == "Pr") {
      m.pr = v;
      m.has_pr = true;
    }
    if (key == "Pm") {
      m.pm = v;
      m.has_pm = true;
    }
  }

  // A texture statement rt2 uses: `KEY [-option values ...] FILE`. Returns false for the
  // others. The file is the last token (names with blanks are not supported).
  bool read_texture(std::string_view key, std::span<const std::string_view> values) {
    MtlMaterial& m = *current_;
    MtlTexture* texture = key == "map_Kd"   ? &m.map_kd
                          : key == "map_Ke" ? &m.map_ke
                          : key == "map_Pr" ? &m.map_pr
                          : key == "map_Pm" ? &m.map_pm
                          : key == "norm"   ? &m.norm
                                            : nullptr;
    if (!texture) return false;
    if (values.empty()) fail(std::string(key) + " needs a file name");
    *texture = MtlTexture{std::string(values.back()), line_};
    for (std::size_t i = 0; i + 2 < values.size(); ++i)
      if (key == "norm" && values[i] == "-bm") m.norm_scale = number("norm -bm", values[i + 1]);
    return true;
  }

  void read_illum(std::span<const std::string_view> values) {
    const std::string got = values.empty() ? "nothing" : "'" + std::string(values[0]) + "'";
    double v = 0.0;
    if (values.size() != 1 || !parse_double(values[0], v) || !(v >= 0 && v <= 10) ||
        v != std::floor(v))
      fail("illum must be an integer from 0 to 10 (got " + got + ")");
    if (current_) current_->illum = static_cast<int>(v);
  }

  const std::string& file_;
  MtlMaterials& wanted_;
  MtlMaterial* current_ = nullptr;        // the material being read, if it is kept
  std::optional<std::string_view> name_;  // the material being read, for messages
  std::size_t line_ = 0;
  std::size_t texture_line_ = 0, spectral_line_ = 0;  // the first, in materials kept
  std::string_view texture_key_;
};

}  // namespace

void read_mtl(const std::string& file, std::string_view text, MtlMaterials& wanted) {
  MtlReader reader(file, wanted);
  for_each_line(text, [&](std::size_t line, std::string_view s) { reader.line(line, s); });
  reader.finish();
}

Material from_mtl(const MtlMaterial& t, const AddTexture& texture) {
  Material m;
  const auto tex = [&](std::string_view key, const MtlTexture& statement, bool srgb) {
    return statement.file.empty() || !texture ? kNoTexture : texture(key, statement, srgb);
  };
  m.base_color_texture = tex("map_Kd", t.map_kd, true);
  if (t.is_pbr()) {
    m.model = Shading::pbr;
    m.base_color = t.has_kd ? color(t.kd) : vec4(1.0f, 1.0f, 1.0f);
    m.metallic = clamp01(t.pm);
    m.roughness = clamp01(t.pr);
    m.emissive = vec4(std::max(t.ke[0], 0.0f), std::max(t.ke[1], 0.0f), std::max(t.ke[2], 0.0f));
    m.emissive_texture = tex("map_Ke", t.map_ke, true);
    m.roughness_texture = tex("map_Pr", t.map_pr, false);
    m.metallic_texture = tex("map_Pm", t.map_pm, false);
    m.normal_texture = tex("norm", t.norm, false);
    m.normal_scale = t.norm_scale;
    if (t.has_ni && t.ni > 0.0f) m.ior = std::min(t.ni, 100.0f);
    // d, else 1 - Tr, below 1: the rest is transmitted
    const float opacity = t.has_d ? clamp01(t.d) : t.has_tr ? clamp01(1.0f - t.tr) : 1.0f;
    m.transmission = 1.0f - opacity;
    m.diffuse = m.base_color * (1.0f - m.metallic);
    return m;
  }
  m.ambient = color(t.ka);
  m.diffuse = t.has_kd || !t.diffuse_texture ? color(t.kd) : vec4(0.6f, 0.6f, 0.6f);
  m.specular = color(t.ks);
  m.shininess = std::clamp(t.ns, 0.0f, 1e4f);
  // Exponent 0 would add Ks over the whole lit side (cos^0 = 1): 3ds Max writes Ns 0 with
  // Ks > 0 for matte surfaces, so 0 means no highlight.
  if (m.shininess == 0.0f) m.specular = vec4(0.0f, 0.0f, 0.0f);
  if (t.has_ni && t.ni > 0.0f) m.ior = std::min(t.ni, 100.0f);
  // d, else 1 − Tr: the opacity.
  const float opacity = t.has_d ? clamp01(t.d) : t.has_tr ? clamp01(1.0f - t.tr) : 1.0f;
  m.transparency = 1.0f - opacity;
  const float ks = std::max({clamp01(t.ks[0]), clamp01(t.ks[1]), clamp01(t.ks[2])});
  switch (t.illum) {
    case 3:
    case 5:  // reflection
      m.reflectivity = ks;
      break;
    case 4:
    case 6:
    case 7:  // glass: an opaque d means the file did not say, not that it is opaque
      m.reflectivity = ks;
      m.transparency = opacity < 1.0f ? 1.0f - opacity : 0.9f;
      break;
    default:
      break;
  }
  if (t.has_kr) m.reflectivity = clamp01(t.kr);
  return m;
}

}  // namespace rt2::io
