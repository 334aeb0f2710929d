// rt2/io/toml_scene.cpp — TOML scene files into rt2::Scene (internal; see
// rt2/io/toml_scene.h).
//
// The file is read and screened here (size, encoding, key depth, and invalid TOML that
// toml++ 3.3 would mishandle: TomlScreen), parsed by toml++, then walked with Reader
// (rt2/io/toml_reader.h), which fetches typed, range-checked values and reports unknown
// keys, so every message can name the file, the line and column and the key path. The
// sections of the scene (camera, world, materials, lights, spheres, planes, meshes) are read
// here; the OBJ files that [[meshes]] name go to rt2/io/obj_mesh.h.
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
#include <system_error>
#include <utility>
#include <vector>

#include "rt2/base/error.h"
#include "rt2/io/obj_mesh.h"
#include "rt2/io/text.h"
#include "rt2/io/toml_reader.h"

namespace rt2::io {
namespace {

namespace fs = std::filesystem;

// Limits beyond which input is a mistake, not a scene.
constexpr std::size_t kMaxSceneBytes = 64u << 20;  // a TOML scene file
constexpr int kMaxKeyDepth = 256;                  // see TomlScreen

// ---- TOML screening -----------------------------------------------------------------------

// toml++ names invalid UTF-8 itself, with its position; these are the cases it reports
// poorly: nothing at all, UTF-16 (a byte-order mark, or NUL bytes), compressed files and
// other binary data.
void check_encoding(const std::string& file, std::string_view text) {
  if (text.empty()) error_at(file, 0, 0, "file is empty");
  const std::string kind = not_text(text);
  if (!kind.empty()) error_at(file, 0, 0, "file is " + kind);
  const std::size_t nul = text.find('\0');
  if (nul != std::string_view::npos) {
    const auto [line, column] = line_and_column(text, nul);
    error_at(file, line, column,
             "file contains a NUL byte: it is binary or UTF-16, but a scene must be UTF-8 text");
  }
}

bool is_digit(char c) { return c >= '0' && c <= '9'; }

// "'x'" for a printable ASCII character, else "a line break", "byte 0xE9".
std::string describe_char(char c) {
  const auto u = static_cast<unsigned char>(c);
  if (c == '\n' || c == '\r') return "a line break";
  if (u > ' ' && u < 0x7f) return "'" + std::string(1, c) + "'";
  static const char* const kHex = "0123456789ABCDEF";
  return std::string("byte 0x") + kHex[u >> 4] + kHex[u & 15];
}

bool is_bare_key_char(char c) {
  return is_digit(c) || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' || c == '-' ||
         c == '+' || c == '.';
}

bool is_blank(char c) { return c == ' ' || c == '\t'; }

// What ends a TOML value (toml++'s is_value_terminator, in ASCII): whitespace, including the
// line breaks and \v and \f, or ] } , #.
bool is_value_end(char c) {
  return c == ' ' || (c >= '\t' && c <= '\r') || c == ']' || c == '}' || c == ',' || c == '#';
}

// "YYYY-MM-DD" (digits and dashes only; toml++ checks the ranges).
bool is_date(std::string_view d) {
  if (d.size() != 10 || d[4] != '-' || d[7] != '-') return false;
  for (const std::size_t k : {0, 1, 2, 3, 5, 6, 8, 9})
    if (!is_digit(d[k])) return false;
  return true;
}

// What toml++ 3.3 takes for a date that a time may follow after a space: 10 characters,
// underscores not counted, of digits and dashes with '-' at 4 and 7. (Wider than its test,
// which also wants a digit first: a wider test only screens more of a value that is invalid.)
bool is_date_like(std::string_view token) {
  std::string d;
  for (const char c : token)
    if (c != '_') d += c;
  if (d.size() != 10 || d[4] != '-' || d[7] != '-') return false;
  return std::all_of(d.begin(), d.end(), [](char c) { return is_digit(c) || c == '-'; });
}

[[noreturn]] void fail_at_byte(const std::string& file, std::string_view text, std::size_t i,
                               const std::string& msg) {
  const auto [line, column] = line_and_column(text, i);
  error_at(file, line, column, msg);
}

// toml++ 3.3 requires (TOML_ASSERT_ASSUME in parser::parse_key) that the key of a table
// header starts with a key character, but parse_table_header does not check it: `[,]`,
// `[[[a]]]` or `[\n` abort a debug build of toml++ and are undefined behaviour in a release
// one (fixed upstream after 3.3, tomlplusplus pull request #301). So the header that starts
// at text[open] (a '[') is checked here as toml++ reads it: '[', blanks, an optional second
// '[' (only right after the first; toml++ reports "[ [" itself) and blanks, then a bare key
// character, a quote, or the ']' that toml++ reports as an empty key.
void check_header_start(const std::string& file, std::string_view text, std::size_t open) {
  std::size_t i = open + 1;
  while (i < text.size() && is_blank(text[i])) ++i;
  if (i < text.size() && text[i] == '[') {
    if (i > open + 1) return;
    ++i;
    while (i < text.size() && is_blank(text[i])) ++i;
  }
  if (i >= text.size()) return;  // toml++ reports the end of the file
  const char c = text[i];
  if (c == ']' || c == '"' || c == '\'' || (is_bare_key_char(c) && c != '.' && c != '+')) return;
  fail_at_byte(file, text, i,
               "invalid TOML: a table header must start with a key (a letter, digit, '_', '-' "
               "or a quote), not " + describe_char(c));
}

// In a multi-line basic string, toml++ 3.3 tests what follows a backslash with is_whitespace
// (is it a line-ending backslash?), and then skips blanks and line breaks with
// is_horizontal_whitespace: for a non-ASCII character either reaches TOML_UNREACHABLE
// (undefined behaviour; see TomlScreen::check_ascii). So the backslash at text[slash] must
// not be followed, after blanks and line breaks, by a non-ASCII character.
void check_line_ending_escape(const std::string& file, std::string_view text, std::size_t slash) {
  const std::size_t i = text.find_first_not_of(" \t\r\n", slash + 1);
  if (i == std::string_view::npos || static_cast<unsigned char>(text[i]) < 0x80) return;
  fail_at_byte(file, text, i,
               "a line-ending backslash in a multi-line string followed by a non-ASCII "
               "character: valid TOML, but toml++ 3.3 cannot read it safely; write the "
               "character as an escape such as \\u00E9");
}

// A lexical pass over a TOML text before toml++ parses it, for what toml++ 3.3 handles badly.
//
// Key depth. toml++ limits nested arrays and inline tables (TOML_MAX_NESTED_VALUES = 256) but
// not dotted keys or table headers: `a.a.a...a = 1` with ~30 000 parts overflows the stack
// inside the parser, which recurses over the finished tree. So the key depth is estimated
// and anything deeper than kMaxKeyDepth is refused. The estimate counts the dots of keys
// outside strings and comments: those of the current table header, plus those of the
// current key in each open array or inline table. The first dot of a token between two
// digits is taken for a decimal point (1.5), so a key made of digits (1.2.3) still counts
// from its second dot: the estimate is at least half the true key depth, which is therefore
// bounded by about 2 * kMaxKeyDepth, far from the overflow.
//
// Inputs that break toml++'s own assertions (abort in a debug build of toml++, undefined
// behaviour in a release one), all found by fuzzing (scripts/fuzz) and all invalid TOML: a
// table header not starting with a key (check_header_start), a '}' where an array expects a
// value (check_closer), a date with a broken time after it (check_date_time), non-ASCII
// outside strings and comments (check_ascii) and after a backslash in a multi-line string
// (check_line_ending_escape). Quotes start strings only where toml++ reads them so
// (opens_string, scanned_value).
class TomlScreen {
 public:
  TomlScreen(const std::string& file, std::string_view text) : file_(file), text_(text) {}

  void run() {
    // toml++ skips a UTF-8 byte-order mark; it is the only non-ASCII allowed outside strings.
    for (i_ = text_.starts_with(kUtf8Bom) ? kUtf8Bom.size() : 0; i_ < text_.size(); ++i_) {
      const char c = text_[i_];
      if (c == '\n')
        newline();
      else if (state_ != State::normal)
        in_comment_or_string(c);
      else
        normal(c);
    }
  }

 private:
  enum class State { normal, comment, basic, literal, ml_basic, ml_literal };

  void newline() {
    if (state_ == State::comment || state_ == State::basic || state_ == State::literal)
      state_ = State::normal;  // a single-line string cannot go on; toml++ reports it
    if (state_ == State::normal && frames_.size() == 1) {
      open_dots_ = frames_[0] = 0;
      in_header_ = false;
      line_start_ = true;
    }
    token_dots_ = 0;
  }

  void in_comment_or_string(char c) {
    if (state_ == State::comment) return;
    const bool basic = state_ == State::basic || state_ == State::ml_basic;
    const bool multi = state_ == State::ml_basic || state_ == State::ml_literal;
    const char quote = basic ? '"' : '\'';
    if (basic && c == '\\') {
      if (multi) check_line_ending_escape(file_, text_, i_);
      ++i_;  // the escaped character cannot end the string
    } else if (multi ? text_.substr(i_, 3) == std::string(3, quote) : c == quote) {
      i_ += multi ? 2 : 0;
      state_ = State::normal;
    }
  }

  void normal(char c) {
    check_ascii(c);
    if ((is_digit(c) || c == '+' || c == '-') && at_value_start()) {
      scanned_value();
      return;
    }
    if (c == '#') {
      state_ = State::comment;
    } else if ((c == '"' || c == '\'') && opens_string()) {
      const bool multi = text_.substr(i_, 3) == std::string(3, c);
      state_ = c == '"' ? (multi ? State::ml_basic : State::basic)
                        : (multi ? State::ml_literal : State::literal);
      i_ += multi ? 2 : 0;
    } else if (c == '[' && line_start_ && frames_.size() == 1) {
      check_header_start(file_, text_, i_);
      in_header_ = true;
      header_dots_ = 0;
    } else if ((c == '[' || c == '{') && !in_header_) {
      frames_.push_back(0);
      openers_.push_back(c);
    } else if ((c == ']' || c == '}') && !in_header_ && frames_.size() > 1) {
      check_closer(c);
      open_dots_ -= frames_.back();
      frames_.pop_back();
      openers_.pop_back();
    } else if (c == ',' && !in_header_) {
      open_dots_ -= frames_.back();
      frames_.back() = 0;
    } else if (c == '.') {
      dot();
    }
    token_dots_ = is_bare_key_char(c) ? token_dots_ + (c == '.') : 0;
    // A comment or a line break (its '\r') between '[' or ',' and a value is blank to toml++:
    // the value after it still starts a value.
    if (!is_blank(c) && c != '\r' && c != '#') {
      line_start_ = false;
      last_ = c;
    }
  }

  // Where a value starts: after '=', or after '[' or ',' in an array.
  bool at_value_start() const {
    return last_ == '=' || ((last_ == '[' || last_ == ',') && !in_header_ && !openers_.empty() &&
                            openers_.back() == '[');
  }

  // A value that starts with a digit or a sign (a number, date or time): toml++ 3.3 scans it
  // to the first value terminator as one token, quotes and brackets included (`x = 0."""é`
  // is one token, not a number and a string), testing each character with
  // is_value_terminator: so no character of it may be non-ASCII (check_ascii). The token is
  // skipped here, so its dots are not keys and its quotes open no string. Valid values
  // contain neither, so only invalid TOML, which toml++ refuses, is read differently.
  //
  // A token of 10 digits and dashes with '-' at 4 and 7 (a date) followed by a space and a
  // digit is a date-time written with a space, and toml++ scans on to the next terminator:
  // so does this.
  void scanned_value() {
    const auto token_end = [&](std::size_t from) {
      while (from < text_.size() && !is_value_end(text_[from])) ++from;
      return from;
    };
    std::size_t end = token_end(i_);
    check_date_time(end);
    if (is_date_like(text_.substr(i_, end - i_)) && end + 1 < text_.size() && text_[end] == ' ' &&
        is_digit(text_[end + 1]))
      end = token_end(end + 1);
    for (; i_ < end; ++i_) check_ascii(text_[i_]);
    --i_;  // run() steps past the token's last character
    last_ = text_[i_];
    line_start_ = false;
    token_dots_ = 0;
  }

  // Two values on which toml++ 3.3 breaks its own assertions: "YYYY-MM-DD" then 'T' (or 't')
  // and no digit (`x = 1979-05-27T:`: parse_date_time calls parse_time, which asserts a
  // digit), and a token, a space, one digit and the value's end (`x = [1979-05-27 1]`: the
  // value scanner, looking for a date-time written with a space, asserts that more follows
  // the digit; it does so for any token of 10 characters with '-' at 4 and 7, so every such
  // value is refused: none is valid TOML). `end` is where the value's first token ends.
  void check_date_time(std::size_t end) const {
    const std::size_t t = i_ + 10;  // after a date
    if (is_date(text_.substr(i_, 10)) && t + 1 < text_.size() &&
        (text_[t] == 'T' || text_[t] == 't') && !is_digit(text_[t + 1]))
      fail_at_byte(file_, text_, t + 1,
                   "invalid TOML: a date-time needs a time (HH:MM) after '" +
                       std::string(1, text_[t]) + "', not " + describe_char(text_[t + 1]));
    if (end + 2 < text_.size() && text_[end] == ' ' && is_digit(text_[end + 1]) &&
        is_value_end(text_[end + 2]))
      fail_at_byte(file_, text_, end + 2,
                   "invalid TOML: a value followed by a space and one digit (a date-time "
                   "needs a time HH:MM after the space)");
  }

  // Whether the quote at text_[i_] starts a string for toml++: only where a key or a value
  // can start. After a token (`x = 1"abc"`, `x = true"é"`) toml++ reads the quote as part of
  // the value, or as an error, not as a string.
  bool opens_string() const {
    const char before = i_ == 0 ? '\n' : text_[i_ - 1];
    return is_blank(before) || before == '\n' || before == '\r' || before == '=' ||
           before == '[' || before == '{' || before == ',' || before == '.' ||
           (i_ == kUtf8Bom.size() && text_.starts_with(kUtf8Bom));
  }

  // TOML allows non-ASCII only in strings and comments, and toml++ 3.3 must not see it
  // elsewhere: its is_non_ascii_horizontal_whitespace reaches TOML_UNREACHABLE (undefined
  // behaviour) for most of U+00A1..U+0499, U+2C3E..U+3037 and U+FB06..U+FEFE.
  void check_ascii(char c) const {
    if (static_cast<unsigned char>(c) < 0x80) return;
    fail_at_byte(file_, text_, i_,
                 "invalid TOML: " + describe_char(c) +
                     " outside a string or comment (only ASCII is allowed there)");
  }

  // toml++ 3.3's parse_array hands a '}' to parse_value, which asserts that it is not a
  // value terminator: `x = [1, }` must be refused here.
  void check_closer(char c) const {
    if (c != '}' || openers_.back() != '[') return;
    fail_at_byte(file_, text_, i_, "invalid TOML: '}' inside an array (expected a value or ']')");
  }

  void dot() {
    const bool decimal_point = token_dots_ == 0 && i_ > 0 && is_digit(text_[i_ - 1]) &&
                               i_ + 1 < text_.size() && is_digit(text_[i_ + 1]);
    if (!decimal_point) {
      if (in_header_) {
        ++header_dots_;
      } else {
        ++frames_.back();
        ++open_dots_;
      }
    }
    if (header_dots_ + open_dots_ > kMaxKeyDepth)
      fail_at_byte(file_, text_, i_,
                   "keys are nested more than " + std::to_string(kMaxKeyDepth) + " levels deep");
  }

  const std::string& file_;
  std::string_view text_;
  std::size_t i_ = 0;
  State state_ = State::normal;
  std::vector<int> frames_{0};  // key dots per open bracket; frames_[0] is the statement
  std::vector<char> openers_;   // the open brackets, '[' or '{', of frames_[1...]
  int open_dots_ = 0;           // the sum of frames_
  int header_dots_ = 0;
  bool in_header_ = false, line_start_ = true;
  int token_dots_ = 0;
  char last_ = '\n';  // the last character outside strings and comments that is not a blank
};

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
  const vec4 given = look_at ? vec4(c.vector("look_at", kAny) - position) : c.vector("direction", kAny);
  if (!(float(dot(given, given)) > 0.0f)) {
    if (look_at) c.fail(*look_at, "camera.look_at must differ from camera.position");
    c.fail(*direction, "camera.direction must not be zero");
  }
  const vec4 forward = normalize(given);

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
    scene.camera = Camera::from_file_values(position, given, up, fov);
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

// The index in scene.textures of the image file `key` names (relative to `folder`), added
// once per file and colour space. The file must exist as a regular file; whether it decodes
// is found when the scene is compiled (rt2/shading/texture.h).
std::uint32_t texture_ref(const Reader& r, Scene& scene, const fs::path& folder,
                          std::string_view key, bool srgb) {
  const std::string path = (folder / r.string(key)).string();
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec || !fs::exists(st))
    r.fail(r.require(key), r.name(key) + ": '" + path + "': no such file");
  if (!fs::is_regular_file(st))
    r.fail(r.require(key), r.name(key) + ": '" + path + "' is not a regular file");
  for (std::size_t i = 0; i < scene.textures.size(); ++i)
    if (scene.textures[i].path == path && scene.textures[i].srgb == srgb)
      return static_cast<std::uint32_t>(i);
  scene.textures.push_back(TextureDesc{path, {}, srgb});
  return static_cast<std::uint32_t>(scene.textures.size() - 1);
}

// The keys of each material model (besides `model`).
const std::initializer_list<std::string_view> kPhongKeys = {
    "model", "ambient", "diffuse", "specular", "shininess", "reflectivity", "transparency",
    "ior", "checker", "diffuse_texture"};
const std::initializer_list<std::string_view> kPbrKeys = {
    "model", "base_color", "metallic", "roughness", "emissive", "transmission", "ior",
    "base_color_texture", "metallic_roughness_texture", "normal_texture", "normal_scale",
    "emissive_texture"};

void read_environment(const Reader& root, Scene& scene, const fs::path& folder) {
  if (!root.find("environment")) return;
  const Reader e = root.table("environment", {"image", "intensity", "rotation", "sun_direction"});
  EnvironmentDesc env;
  if (e.find("image")) {
    env.image = (folder / e.string("image")).string();
    std::error_code ec;
    if (!fs::is_regular_file(env.image, ec))
      e.fail(e.require("image"), e.name("image") + ": '" + env.image + "' is not a readable file");
  }
  env.intensity = e.number("intensity", env.intensity, kNonNegative);
  env.rotation_degrees = e.number("rotation", env.rotation_degrees, kAny);
  env.sun_direction = e.vector("sun_direction", env.sun_direction, kAny);
  if (!(float(dot(env.sun_direction, env.sun_direction)) > 0.0f))
    e.fail(e.require("sun_direction"), "environment.sun_direction must not be zero");
  scene.environment = env;
}

Material read_pbr_material(const Reader& r, Scene& scene, const fs::path& folder) {
  Material m;
  m.model = Shading::pbr;
  m.base_color = r.vector("base_color", m.base_color, kNonNegative);
  m.metallic = r.number("metallic", m.metallic, kUnit);
  m.roughness = r.number("roughness", m.roughness, kUnit);
  m.emissive = r.vector("emissive", m.emissive, kNonNegative);
  m.transmission = r.number("transmission", m.transmission, kUnit);
  m.ior = r.number("ior", m.ior, kIor);
  m.normal_scale = r.number("normal_scale", m.normal_scale, kAny);
  const auto texture = [&](std::string_view key, bool srgb) {
    return r.find(key) ? texture_ref(r, scene, folder, key, srgb) : kNoTexture;
  };
  m.base_color_texture = texture("base_color_texture", true);
  m.metallic_roughness_texture = texture("metallic_roughness_texture", false);
  m.normal_texture = texture("normal_texture", false);
  m.emissive_texture = texture("emissive_texture", true);
  m.diffuse = m.base_color * (1.0f - m.metallic);  // what a Phong view of it would show
  return m;
}

Material read_material(const Reader& r, Scene& scene, const fs::path& folder) {
  Material m;
  if (r.find("diffuse_texture"))
    m.base_color_texture = texture_ref(r, scene, folder, "diffuse_texture", true);
  m.ambient = r.vector("ambient", m.ambient, kNonNegative);
  m.diffuse = r.vector("diffuse", m.diffuse, kNonNegative);
  m.specular = r.vector("specular", m.specular, kNonNegative);
  m.shininess = r.number("shininess", m.shininess, kNonNegative);
  m.reflectivity = r.number("reflectivity", m.reflectivity, kUnit);
  m.transparency = r.number("transparency", m.transparency, kUnit);
  m.ior = r.number("ior", m.ior, kIor);
  if (r.find("checker")) {
    const Reader c = r.table("checker", {"color", "scale"});
    m.diffuse2 = c.vector("color", m.diffuse2, kNonNegative);
    m.checker_scale = c.number("scale", 1.0f, kPositive);
  }
  return m;
}

void read_materials(const Reader& root, Scene& scene, const fs::path& folder) {
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
    const toml::node* model_node = mt->get("model");
    const bool pbr = model_node && model_node->value<std::string>() == "pbr";
    const Reader r(root.file(), *mt, "materials." + name, pbr ? kPbrKeys : kPhongKeys);
    if (model_node && !pbr && r.string("model") != "phong")
      r.fail(*model_node, r.name("model") + " must be \"phong\" or \"pbr\"");
    scene.add_material(name, pbr ? read_pbr_material(r, scene, folder)
                                 : read_material(r, scene, folder));
  }
}

void read_lights(const Reader& root, Scene& scene) {
  for_each_table(root, "lights", {"position", "color", "intensity", "range"}, [&](const Reader& r) {
    Light l;
    l.position = r.vector("position", kAny);
    l.color = r.vector("color", l.color, kNonNegative);
    l.intensity = r.number("intensity", l.intensity, kNonNegative);
    l.range = r.number("range", l.range, kPositive);
    scene.lights.push_back(l);
  });
}

// An integer in [lo, hi].
std::int64_t integer(const Reader& r, std::string_view key, std::int64_t lo, std::int64_t hi) {
  const toml::node& n = r.require(key);
  const auto* v = n.as_integer();
  if (!v) r.fail(n, r.name(key) + " must be an integer (got " + type_name(n) + ")");
  if (v->get() < lo || v->get() > hi)
    r.fail(n, r.name(key) + " must be in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                  "], got " + std::to_string(v->get()));
  return v->get();
}

// [light_field]: `count` lights scattered in the box [min, max] (rt2/scene/light_field.h),
// added after the [[lights]].
void read_light_field(const Reader& root, Scene& scene) {
  if (!root.find("light_field")) return;
  const Reader r = root.table("light_field",
                              {"count", "min", "max", "range", "color", "intensity", "seed"});
  LightField f;
  const auto count = static_cast<std::size_t>(integer(r, "count", 0, 1'000'000));
  f.box.lo = r.vector("min", kAny);
  f.box.hi = r.vector("max", kAny);
  for (int a = 0; a < 3; ++a)
    if (!(f.box.lo[a] <= f.box.hi[a]))
      r.fail(r.require("max"), r.name("max") + " must be >= min on every axis");
  const toml::node& range = r.require("range");
  if (const toml::array* a = range.as_array()) {
    if (a->size() != 2)
      r.fail(range, r.name("range") + " must be a number or an array of 2 numbers [lo, hi]");
    f.range_lo = to_number(r.file(), *a->get(0), r.name("range") + "[0]", kPositive);
    f.range_hi = to_number(r.file(), *a->get(1), r.name("range") + "[1]", kPositive);
    if (!(f.range_lo <= f.range_hi)) r.fail(range, r.name("range") + " must have lo <= hi");
  } else {
    f.range_lo = f.range_hi = r.number("range", kPositive);
  }
  f.color = r.vector("color", f.color, kNonNegative);
  f.intensity = r.number("intensity", f.intensity, kNonNegative);
  if (r.find("seed")) f.seed = static_cast<std::uint64_t>(integer(r, "seed", 0, INT64_MAX));
  f.first = scene.lights.size();
  scene.light_field = f;
  for (std::size_t k = 0; k < count; ++k) scene.lights.push_back(f.light(k));
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

// Whether `path` lies under a folder data/meshes/, which scripts/fetch-meshes fills.
bool fetched_mesh(const std::string& path) {
  bool data = false;
  for (const fs::path& part : fs::path(path).lexically_normal()) {
    if (data && part == "meshes") return true;
    data = part == "data";
  }
  return false;
}

// Reads `path` as an OBJ mesh for [[meshes]] and [[instances]] (`key`: the key that names
// it, for messages).
Mesh read_obj_file(const Reader& r, std::string_view key, const std::string& path, Scene& scene,
                   int override_material) {
  std::error_code ec;
  if (fs::status(path, ec).type() == fs::file_type::not_found && fetched_mesh(path))
    throw Error(one_line(r.locate(key) + " '" + path +
                         "': file not found (scripts/fetch-meshes fetches data/meshes/)"));
  return obj_to_mesh(path, read_text_file(path, kMaxObjBytes, r.locate(key)), scene,
                     override_material);
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

        Mesh mesh = read_obj_file(r, "file", path, scene, override_material);
        apply_transform(mesh, xf);
        if (!std::all_of(mesh.positions.begin(), mesh.positions.end(),
                         [](const vec4& p) { return finite(p); }))
          r.fail_table(r.path() + ": the transform makes vertices of '" + path + "' non-finite");
        const AreaOutOfRange range = area_out_of_range(mesh);
        scene.degenerate_triangles += mesh.drop_degenerate();  // a tiny scale can flatten faces
        if (mesh.faces.empty())
          r.fail_table(r.path() + ": every face of '" + path +
                       "' is degenerate after the transform" + degenerate_reason(mesh, range));
        scene.meshes.push_back(std::move(mesh));
      });
}

// An instance's transform: `matrix` (3 or 4 rows of 4 numbers, row-major; a fourth row must
// be 0 0 0 1), or scale, rotate and translate as [[meshes]] takes them.
Affine read_placement(const Reader& r) {
  const toml::node* m = r.find("matrix");
  if (!m) {
    Transform xf;
    xf.scale = read_scale(r);
    xf.rotate_degrees = r.vector("rotate", xf.rotate_degrees, kAny);
    xf.translate = r.vector("translate", xf.translate, kAny);
    return affine_of(xf);
  }
  for (const char* other : {"scale", "rotate", "translate"})
    if (r.find(other))
      r.fail(*r.find(other), r.path() + ": give matrix or " + other + ", not both");
  const toml::array* rows = m->as_array();
  if (!rows || (rows->size() != 3 && rows->size() != 4))
    r.fail(*m, r.name("matrix") + " must be 3 or 4 rows of 4 numbers");
  Affine a;
  for (std::size_t i = 0; i < rows->size(); ++i) {
    const toml::array* row = (*rows)[i].as_array();
    const std::string at = r.name("matrix") + "[" + std::to_string(i) + "]";
    if (!row || row->size() != 4) r.fail((*rows)[i], at + " must be a row of 4 numbers");
    for (std::size_t j = 0; j < 4; ++j) {
      const double x = to_number(r.file(), (*row)[j], at + "[" + std::to_string(j) + "]", kAny);
      if (i < 3)
        a.m[i][j] = x;
      else if (x != (j == 3 ? 1.0 : 0.0))
        r.fail((*row)[j], at + " must be 0 0 0 1 (an affine transform)");
    }
  }
  return a;
}

// [[instances]]: a mesh file placed by a transform; each file is read once, however many
// instances name it (with its own MTL materials), and traced through one tree.
void read_instances(const Reader& root, Scene& scene, const fs::path& folder) {
  struct Loaded {
    std::string path;
    std::uint32_t mesh;
    AreaRange areas;
  };
  std::vector<Loaded> loaded;
  for_each_table(
      root, "instances", {"mesh", "material", "scale", "rotate", "translate", "matrix"},
      [&](const Reader& r) {
        const std::string path = (folder / r.string("mesh")).string();
        Instance in;
        if (r.find("material")) in.material = material_ref(r, scene, "material");
        in.to_world = read_placement(r);
        if (!in.to_world.finite())
          r.fail_table(r.path() + ": the transform is not finite in double precision");
        const double det = in.to_world.determinant();
        if (!std::isnormal(det) || !in.to_world.inverse().finite())
          r.fail_table(r.path() + ": the transform is singular (determinant " +
                       std::to_string(det) + ")");
        auto it = std::find_if(loaded.begin(), loaded.end(),
                               [&](const Loaded& e) { return e.path == path; });
        if (it == loaded.end()) {
          Mesh mesh = read_obj_file(r, "mesh", path, scene, -1);
          scene.degenerate_triangles += mesh.drop_degenerate();
          if (mesh.faces.empty()) r.fail(r.require("mesh"), "'" + path + "' has no triangles");
          const AreaRange areas = area_range(mesh);
          scene.instanced_meshes.push_back(std::move(mesh));
          loaded.push_back({path, std::uint32_t(scene.instanced_meshes.size() - 1), areas});
          it = loaded.end() - 1;
        }
        in.mesh = it->mesh;
        const Aabb box = world_box(scene.instanced_meshes[in.mesh].bounds(), in.to_world);
        if (!finite(box.lo) || !finite(box.hi))
          r.fail_table(r.path() + ": the transform takes '" + path + "' beyond float range");
        if (!areas_fit_float(it->areas, in.to_world))
          r.fail_table(r.path() + ": the transform makes triangles of '" + path +
                       "' too large or too small for float arithmetic");
        scene.instances.push_back(in);
      });
}

}  // namespace

Scene read_toml_scene(const std::string& path, const AssetPolicy& policy) {
  const std::string text = read_file(path, kMaxSceneBytes, "");
  check_encoding(path, text);
  TomlScreen(path, text).run();
  const toml::table doc = parse_toml(path, text);
  const Reader root(path, doc, "",
                    {"camera", "world", "environment", "materials", "lights", "light_field",
                     "spheres", "planes", "meshes", "instances"});
  Scene scene;
  scene.assets = policy;
  read_camera(root, scene);
  read_world(root, scene);
  const fs::path folder = fs::path(path).parent_path();
  read_environment(root, scene, folder);
  read_materials(root, scene, folder);  // first, so that objects can name them wherever they are
  read_lights(root, scene);
  read_light_field(root, scene);
  read_spheres(root, scene);
  read_planes(root, scene);
  read_meshes(root, scene, folder);
  read_instances(root, scene, folder);
  validate(path, scene);
  return scene;
}

Camera read_toml_camera(const std::string& path) {
  const std::string text = read_file(path, kMaxSceneBytes, "");
  check_encoding(path, text);
  TomlScreen(path, text).run();
  const toml::table doc = parse_toml(path, text);
  Scene scene;
  read_camera(Reader(path, doc, "", {"camera"}), scene);
  return scene.camera;
}

}  // namespace rt2::io
