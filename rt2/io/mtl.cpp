// rt2/io/mtl.cpp — the MTL → Material mapping of scenes/FORMAT.md and the scan of MTL text
// for the facts tinyobjloader does not report (internal; see rt2/io/mtl.h).
#include "rt2/io/mtl.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "rt2/io/text.h"

namespace rt2::io {
namespace {

float clamp_or(float v, float lo, float hi, float fallback) {
  return std::isnan(v) ? fallback : std::clamp(v, lo, hi);
}

vec4 mtl_color(const tinyobj::real_t c[3]) {
  return vec4(clamp_or(c[0], 0, 1, 0), clamp_or(c[1], 0, 1, 0), clamp_or(c[2], 0, 1, 0));
}

// Kr (an rt2 extension): one number, or three of which the largest counts.
float mtl_kr(const std::string& value, const MtlFacts& facts, const std::string& material) {
  const std::vector<std::string_view> t = split_blanks(value);
  float kr = 0.0f;
  for (const std::string_view v : t) {
    double x = 0.0;
    if (!parse_double(v, x) || std::isnan(x))
      error_at(facts.file, facts.kr_line, 0,
               "material '" + material + "': Kr must be a number (got '" + value + "')");
    kr = std::max(kr, clamp_or(static_cast<float>(x), 0, 1, 0));
  }
  if (t.empty())
    error_at(facts.file, facts.kr_line, 0, "material '" + material + "': Kr needs a value");
  return kr;
}

}  // namespace

std::string_view newmtl_name(std::string_view line) {
  if (!line.starts_with("newmtl ") && !line.starts_with("newmtl\t")) return {};
  const std::string_view rest = line.substr(7);
  const std::size_t first = rest.find_first_not_of(" \t");  // the line's end is trimmed
  return first == std::string_view::npos ? std::string_view() : rest.substr(first);
}

std::string normalize_mtl(std::string_view text) {
  std::string out;
  out.reserve(text.size() + 1);
  for_each_line(text, [&](std::size_t, std::string_view s) {
    const std::string_view name = newmtl_name(s);
    if (name.empty())
      out += s;
    else
      out.append("newmtl ").append(name);
    out += '\n';
  });
  return out;
}

void scan_mtl(const std::string& file, std::string_view text,
              std::map<std::string, MtlFacts>& facts) {
  MtlFacts* current = nullptr;
  for_each_line(text, [&](std::size_t line, std::string_view s) {
    if (s.starts_with('#')) return;
    const std::string_view name = newmtl_name(s);
    if (!name.empty()) {
      current = &facts[std::string(name)];
      *current = MtlFacts{file};
      return;
    }
    // Values and texture options: tinyobjloader may read any of them as a number.
    check_exponents(file, line, split_blanks(s));
    if (current && (s.starts_with("Ni ") || s.starts_with("Ni\t"))) {
      current->has_ni = true;
    } else if (current && (s.starts_with("Kr ") || s.starts_with("Kr\t"))) {
      current->kr_line = line;
    }
  });
}

Material from_mtl(const tinyobj::material_t& t, const MtlFacts& facts) {
  Material m;
  m.ambient = mtl_color(t.ambient);
  m.diffuse = mtl_color(t.diffuse);
  m.specular = mtl_color(t.specular);
  m.shininess = clamp_or(t.shininess, 0.0f, 1e4f, m.shininess);
  if (facts.has_ni && t.ior > 0.0f && std::isfinite(t.ior)) m.ior = std::min(t.ior, 100.0f);
  const float opacity = clamp_or(t.dissolve, 0.0f, 1.0f, 1.0f);  // d, or 1 - Tr
  m.transparency = 1.0f - opacity;
  const float ks = std::max({m.specular[0], m.specular[1], m.specular[2]});
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
  const auto kr = t.unknown_parameter.find("Kr");
  if (kr != t.unknown_parameter.end()) m.reflectivity = mtl_kr(kr->second, facts, t.name);
  return m;
}

}  // namespace rt2::io
