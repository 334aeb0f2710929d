// rt2/io/toml_scene.cpp — TOML scene files into rt2::Scene (internal; see
// rt2/io/toml_scene.h).
//
// The file is read and screened here (size, encoding, key depth), parsed by toml++, then
// walked with Reader (rt2/io/toml_reader.h), which fetches typed, range-checked values and
// reports unknown keys, so every message can name the file, the line and column and the key
// path. The sections of the scene (camera, world, materials, lights, spheres, planes,
// meshes) are read here; the OBJ files that [[meshes]] name go to rt2/io/obj_mesh.h.
#include "rt2/io/toml_scene.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rt2/error.h"
#include "rt2/io/obj_mesh.h"
#include "rt2/io/text.h"
#include "rt2/io/toml_reader.h"

namespace rt2::io {
namespace {

namespace fs = std::filesystem;

// Limits beyond which input is a mistake, not a scene.
constexpr std::size_t kMaxSceneBytes = 64u << 20;  // a TOML scene file
constexpr int kMaxKeyDepth = 256;                  // see check_key_depth

// ---- TOML screening -----------------------------------------------------------------------

// toml++ names invalid UTF-8 itself, with its position; these are the cases it reports
// poorly: nothing at all, UTF-16 (a byte-order mark, or NUL bytes), and binary data.
void check_encoding(const std::string& file, std::string_view text) {
  if (text.empty()) error_at(file, 0, 0, "file is empty");
  if (text.starts_with("\xFF\xFE") || text.starts_with("\xFE\xFF"))
    error_at(file, 0, 0,
             "file is UTF-16 (it starts with a UTF-16 byte-order mark); save it as UTF-8");
  const std::size_t nul = text.find('\0');
  if (nul != std::string_view::npos) {
    const auto [line, column] = line_and_column(text, nul);
    error_at(file, line, column,
             "file contains a NUL byte: it is binary or UTF-16, but a scene must be UTF-8 text");
  }
}

bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_bare_key_char(char c) {
  return is_digit(c) || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' || c == '-' ||
         c == '+' || c == '.';
}

// toml++ limits nested arrays and inline tables (TOML_MAX_NESTED_VALUES = 256) but not
// dotted keys or table headers: `a.a.a...a = 1` with ~30 000 parts overflows the stack
// inside the parser, which recurses over the finished tree. So the key depth is estimated
// lexically before parsing and anything deeper than kMaxKeyDepth is refused. The estimate
// counts the dots of keys outside strings and comments: those of the current table header,
// plus those of the current key in each open array or inline table. The first dot of a
// token between two digits is taken for a decimal point (1.5), so a key made of digits
// (1.2.3) still counts from its second dot: the estimate is at least half the true key
// depth, which is therefore bounded by about 2 * kMaxKeyDepth, far from the overflow.
void check_key_depth(const std::string& file, std::string_view text) {
  enum class State { normal, comment, basic, literal, ml_basic, ml_literal };
  State state = State::normal;
  std::vector<int> frames{0};  // key dots per open bracket; frames[0] is the statement
  int open_dots = 0;           // the sum of frames
  int header_dots = 0;
  bool in_header = false, line_start = true;
  int token_dots = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      if (state == State::comment || state == State::basic || state == State::literal)
        state = State::normal;  // a single-line string cannot go on; toml++ reports it
      if (state == State::normal && frames.size() == 1) {
        open_dots = frames[0] = 0;
        in_header = false;
        line_start = true;
      }
      token_dots = 0;
      continue;
    }
    switch (state) {
      case State::comment:
        continue;
      case State::basic:
      case State::ml_basic:
        if (c == '\\') {
          ++i;
        } else if (state == State::basic ? c == '"' : text.substr(i, 3) == "\"\"\"") {
          i += state == State::basic ? 0 : 2;
          state = State::normal;
        }
        continue;
      case State::literal:
      case State::ml_literal:
        if (state == State::literal ? c == '\'' : text.substr(i, 3) == "'''") {
          i += state == State::literal ? 0 : 2;
          state = State::normal;
        }
        continue;
      case State::normal:
        break;
    }
    if (c == '#') {
      state = State::comment;
    } else if (c == '"' || c == '\'') {
      const bool multi = text.substr(i, 3) == std::string(3, c);
      state = c == '"' ? (multi ? State::ml_basic : State::basic)
                       : (multi ? State::ml_literal : State::literal);
      i += multi ? 2 : 0;
    } else if (c == '[' && line_start && frames.size() == 1) {
      in_header = true;
      header_dots = 0;
    } else if ((c == '[' || c == '{') && !in_header) {
      frames.push_back(0);
    } else if ((c == ']' || c == '}') && !in_header && frames.size() > 1) {
      open_dots -= frames.back();
      frames.pop_back();
    } else if (c == ',' && !in_header) {
      open_dots -= frames.back();
      frames.back() = 0;
    } else if (c == '.') {
      const bool decimal_point = token_dots == 0 && i > 0 && is_digit(text[i - 1]) &&
                                 i + 1 < text.size() && is_digit(text[i + 1]);
      if (!decimal_point) {
        if (in_header) {
          ++header_dots;
        } else {
          ++frames.back();
          ++open_dots;
        }
      }
      if (header_dots + open_dots > kMaxKeyDepth) {
        const auto [line, column] = line_and_column(text, i);
        error_at(file, line, column,
                 "keys are nested more than " + std::to_string(kMaxKeyDepth) + " levels deep");
      }
    }
    token_dots = is_bare_key_char(c) ? token_dots + (c == '.') : 0;
    if (c != ' ' && c != '\t') line_start = false;
  }
}

toml::table parse_toml(const std::string& file, const std::string& text) {
  try {
    return toml::parse(std::string_view(text), std::string_view(file));
  } catch (const toml::parse_error& e) {
    error_at(file, e.source().begin.line, e.source().begin.column,
             "invalid TOML: " + std::string(e.description()));
  }
}

// ---- TOML scene sections ----------------------------------------------------------------

// Calls fn(Reader) for each table of the array `key` (written [[key]] or key = [{...}]).
template <class Fn>
void for_each_table(const Reader& root, std::string_view key,
                    std::initializer_list<std::string_view> keys, Fn&& fn) {
  const toml::node* n = root.find(key);
  if (!n) return;
  const std::string k(key);
  const toml::array* a = n->as_array();
  if (!a)
    root.fail(*n,
              k + " must be an array of tables, written [[" + k + "]] (got " + type_name(*n) + ")");
  for (std::size_t i = 0; i < a->size(); ++i) {
    const std::string name = k + "[" + std::to_string(i) + "]";
    const toml::table* t = (*a)[i].as_table();
    if (!t) root.fail((*a)[i], name + " must be a table (got " + type_name((*a)[i]) + ")");
    fn(Reader(root.file(), *t, name, keys));
  }
}

std::uint32_t material_ref(const Reader& r, const Scene& scene, std::string_view key) {
  const std::string name = r.string(key);
  const int m = scene.find_material(name);
  if (m < 0) {
    r.fail(r.require(key), r.name(key) + ": undefined material '" + name + "'" +
                               suggestion(name, scene.material_names));
  }
  return static_cast<std::uint32_t>(m);
}

void read_camera(const Reader& root, Scene& scene) {
  if (!root.find("camera")) error_at(root.file(), 0, 0, "missing required table [camera]");
  const Reader c = root.table("camera", {"position", "look_at", "direction", "up", "fov"});
  const vec4 position = c.vector("position", kAny);
  const toml::node* look_at = c.find("look_at");
  const toml::node* direction = c.find("direction");
  if (look_at && direction) c.fail(*direction, "camera: give look_at or direction, not both");
  if (!look_at && !direction) c.fail_table("camera needs look_at or direction (one of the two)");
  vec4 forward = look_at ? vec4(c.vector("look_at", kAny) - position) : c.vector("direction", kAny);
  if (!(float(dot(forward, forward)) > 0.0f)) {
    if (look_at) c.fail(*look_at, "camera.look_at must differ from camera.position");
    c.fail(*direction, "camera.direction must not be zero");
  }
  forward = normalize(forward);

  const toml::node* up_node = c.find("up");
  const vec4 up = c.vector("up", vec4(0.0f, 1.0f, 0.0f), kAny);
  if (!(float(dot(up, up)) > 0.0f)) c.fail(*up_node, "camera.up must not be zero");
  const vec4 unit_up = normalize(up);
  const vec4 side = cross(forward, unit_up);
  if (!(float(dot(side, side)) > 1e-8f)) {  // sin(angle) <= 1e-4
    if (up_node) c.fail(*up_node, "camera.up is parallel to the view direction");
    c.fail_table(
        "camera looks straight up or down, parallel to the default up [0, 1, 0]; set camera.up");
  }
  const float fov = c.number("fov", 60.0f, kFov);
  try {
    scene.camera = Camera(position, forward, unit_up, fov);
  } catch (const Error& e) {  // checked above; kept so a message could never lose its place
    c.fail_table(std::string("camera: ") + e.what());
  }
}

void read_world(const Reader& root, Scene& scene) {
  if (!root.find("world")) return;
  const Reader w = root.table("world", {"ambient", "background"});
  scene.ambient = w.vector("ambient", scene.ambient, kNonNegative);
  scene.background = w.vector("background", scene.background, kNonNegative);
}

Material read_material(const Reader& r) {
  Material m;
  m.ambient = r.vector("ambient", m.ambient, kNonNegative);
  m.diffuse = r.vector("diffuse", m.diffuse, kNonNegative);
  m.specular = r.vector("specular", m.specular, kNonNegative);
  m.shininess = r.number("shininess", m.shininess, kNonNegative);
  m.reflectivity = r.number("reflectivity", m.reflectivity, kUnit);
  m.transparency = r.number("transparency", m.transparency, kUnit);
  m.ior = r.number("ior", m.ior, kPositive);
  if (r.find("checker")) {
    const Reader c = r.table("checker", {"color", "scale"});
    m.diffuse2 = c.vector("color", m.diffuse2, kNonNegative);
    m.checker_scale = c.number("scale", 1.0f, kPositive);
  }
  return m;
}

void read_materials(const Reader& root, Scene& scene) {
  const toml::node* n = root.find("materials");
  if (!n) return;
  const toml::table* t = n->as_table();
  if (!t)
    root.fail(*n,
              "materials must be a table of [materials.NAME] tables (got " + type_name(*n) + ")");
  for (auto&& [key, value] : *t) {
    const std::string name(key.str());
    const toml::table* mt = value.as_table();
    if (!mt)
      root.fail(value, "materials." + name + " must be a table (got " + type_name(value) + ")");
    const Reader r(root.file(), *mt, "materials." + name,
                   {"ambient", "diffuse", "specular", "shininess", "reflectivity", "transparency",
                    "ior", "checker"});
    scene.add_material(name, read_material(r));
  }
}

void read_lights(const Reader& root, Scene& scene) {
  for_each_table(root, "lights", {"position", "color", "intensity"}, [&](const Reader& r) {
    Light l;
    l.position = r.vector("position", kAny);
    l.color = r.vector("color", l.color, kNonNegative);
    l.intensity = r.number("intensity", l.intensity, kNonNegative);
    scene.lights.push_back(l);
  });
}

void read_spheres(const Reader& root, Scene& scene) {
  for_each_table(root, "spheres", {"center", "radius", "material"}, [&](const Reader& r) {
    Sphere s;
    s.center = r.vector("center", kAny);
    s.radius = r.number("radius", kPositive);
    const std::uint32_t m = material_ref(r, scene, "material");
    scene.spheres.push_back(s);
    scene.sphere_materials.push_back(m);
  });
}

// N·X + offset = 0 with N as written: dividing by |N| keeps the same plane. A normal shorter
// than 1e-12 counts as zero (offset / |N| would overflow a float).
void read_planes(const Reader& root, Scene& scene) {
  for_each_table(root, "planes", {"normal", "offset", "point", "material"}, [&](const Reader& r) {
    const vec4 normal = r.vector("normal", kAny);
    const double x = normal[0], y = normal[1], z = normal[2];
    const double length = std::sqrt(x * x + y * y + z * z);
    if (!(length >= 1e-12)) r.fail(r.require("normal"), r.name("normal") + " must not be zero");
    const toml::node* offset = r.find("offset");
    const toml::node* point = r.find("point");
    if (offset && point) r.fail(*point, r.path() + ": give offset or point, not both");
    if (!offset && !point) r.fail_table(r.path() + " needs offset or point (one of the two)");
    Plane p;
    p.n = vec4(float(x / length), float(y / length), float(z / length));
    p.d = offset ? float(r.number("offset", kAny) / length)
                 : -float(dot(p.n, r.vector("point", kAny)));
    const std::uint32_t m = material_ref(r, scene, "material");
    scene.planes.push_back(p);
    scene.plane_materials.push_back(m);
  });
}

// `scale` is a number or a vector, never zero in any axis (the mesh would be flat).
vec4 read_scale(const Reader& r) {
  const toml::node* n = r.find("scale");
  if (!n) return vec4(1.0f, 1.0f, 1.0f);
  if (!n->is_array()) {
    const float s = to_number(r.file(), *n, r.name("scale"), kAny);
    if (s == 0.0f) r.fail(*n, r.name("scale") + " must not be zero");
    return vec4(s, s, s);
  }
  const vec4 s = r.vector("scale", kAny);
  for (std::size_t i = 0; i < 3; ++i)
    if (s[i] == 0.0f)
      r.fail((*n->as_array())[i], r.name("scale") + "[" + std::to_string(i) + "] must not be zero");
  return s;
}

bool finite(const vec4& v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]) && std::isfinite(v[3]);
}

void read_meshes(const Reader& root, Scene& scene, const fs::path& folder) {
  for_each_table(
      root, "meshes", {"file", "material", "scale", "rotate", "translate"}, [&](const Reader& r) {
        const std::string path = (folder / r.string("file")).string();
        const int override_material =
            r.find("material") ? static_cast<int>(material_ref(r, scene, "material")) : -1;
        Transform xf;
        xf.scale = read_scale(r);
        xf.rotate_degrees = r.vector("rotate", xf.rotate_degrees, kAny);
        xf.translate = r.vector("translate", xf.translate, kAny);

        Mesh mesh = obj_to_mesh(path, read_file(path, kMaxObjBytes, r.locate("file")), scene,
                                override_material);
        apply_transform(mesh, xf);
        if (!std::all_of(mesh.positions.begin(), mesh.positions.end(),
                         [](const vec4& p) { return finite(p); }))
          r.fail_table(r.path() + ": the transform makes vertices of '" + path + "' non-finite");
        scene.degenerate_triangles += mesh.drop_degenerate();  // a tiny scale can flatten faces
        if (mesh.faces.empty())
          r.fail_table(r.path() + ": every face of '" + path +
                       "' is degenerate after the transform");
        scene.meshes.push_back(std::move(mesh));
      });
}

}  // namespace

Scene read_toml_scene(const std::string& path) {
  const std::string text = read_file(path, kMaxSceneBytes, "");
  check_encoding(path, text);
  check_key_depth(path, text);
  const toml::table doc = parse_toml(path, text);
  const Reader root(path, doc, "",
                    {"camera", "world", "materials", "lights", "spheres", "planes", "meshes"});
  Scene scene;
  read_camera(root, scene);
  read_world(root, scene);
  read_materials(root, scene);  // first, so that objects can name them wherever they are
  read_lights(root, scene);
  read_spheres(root, scene);
  read_planes(root, scene);
  read_meshes(root, scene, fs::path(path).parent_path());
  validate(path, scene);
  return scene;
}

}  // namespace rt2::io
