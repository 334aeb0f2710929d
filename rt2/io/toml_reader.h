// rt2/io/toml_reader.h — typed, range-checked values from a parsed TOML table (internal).
//
// Part of the implementation of rt2/io/scene_io.h, not an API. Reader wraps one toml++ table
// of a scene file: it refuses unknown keys up front (with a "did you mean" hint), fetches
// numbers and 3-vectors within a Limit, strings and sub-tables, and fails with a one-line
// rt2::Error naming the file, the line and column and the key path ("spheres[1].radius").
// What a scene contains is not known here (see rt2/io/toml_scene.cpp).
#pragma once

#include <toml++/toml.h>

#include <algorithm>
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>

#include "rt2/io/text.h"
#include "rt2/geometry/ray.h"

namespace rt2::io {

// Limits beyond which input is a mistake, not a scene.
constexpr double kMaxMagnitude = 1e15;  // any number in a scene file

// ---- TOML values ------------------------------------------------------------------------

// An allowed range of a number (beyond the magnitude limit that every number has).
struct Limit {
  double lo = -kMaxMagnitude, hi = kMaxMagnitude;
  bool lo_open = false, hi_open = false;

  bool contains(double v) const {
    return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  }
  std::string text() const {
    if (hi == kMaxMagnitude) return (lo_open ? "> " : ">= ") + fmt(lo);
    return "in " + std::string(lo_open ? "(" : "[") + fmt(lo) + ", " + fmt(hi) +
           (hi_open ? ")" : "]");
  }
};

constexpr Limit kAny{};
constexpr Limit kNonNegative{0.0};
constexpr Limit kPositive{0.0, kMaxMagnitude, true};
constexpr Limit kUnit{0.0, 1.0};
constexpr Limit kFov{0.0, 180.0, true, true};
constexpr Limit kIor{0.0, 100.0, true, false};  // as MTL's Ni (rt2/io/mtl.h): beyond, no glass

// "a table", "an integer", ...: the type of `n`, for messages.
std::string type_name(const toml::node& n);

// "file:line:column" of the start of `r`.
std::string node_location(const std::string& file, const toml::source_region& r);

// Throws rt2::Error "file:line:column: msg" at the position of `n`, made one line.
[[noreturn]] void fail_at(const std::string& file, const toml::node& n, const std::string& msg);

// A finite number (integers allowed) of magnitude <= kMaxMagnitude within `limit`, checked
// after rounding to float (so 1e-300 is not > 0).
float to_number(const std::string& file, const toml::node& n, const std::string& name,
                const Limit& limit);

// An array of exactly 3 numbers, each checked as by to_number (named "name[i]").
vec4 to_vector(const std::string& file, const toml::node& n, const std::string& name,
               const Limit& limit);

// A checked view of one TOML table: typed values with range checks, and messages naming the
// file, the position and the key path ("spheres[1].radius"). The allowed keys are given up
// front and checked at once, so a typo (`radious`) is reported as such rather than as the
// "missing key" it would otherwise cause.
class Reader {
 public:
  Reader(const std::string& file, const toml::table& table, std::string path,
         std::initializer_list<std::string_view> keys)
      : file_(file), table_(table), path_(std::move(path)) {
    const toml::key* unknown = nullptr;  // the first in the file, so messages are stable
    for (auto&& [key, value] : table_) {
      if (std::find(keys.begin(), keys.end(), key.str()) != keys.end()) continue;
      const auto& p = key.source().begin;
      if (!unknown || std::pair(p.line, p.column) <
                          std::pair(unknown->source().begin.line, unknown->source().begin.column))
        unknown = &key;
    }
    if (unknown) {
      const auto& p = unknown->source().begin;
      error_at(file_, p.line, p.column,
               "unknown key '" + std::string(unknown->str()) + "'" +
                   (path_.empty() ? "" : " in " + path_) + suggestion(unknown->str(), keys));
    }
  }

  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  std::string name(std::string_view key) const {
    return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
  }

  const toml::node* find(std::string_view key) const { return table_.get(key); }
  const toml::node& require(std::string_view key) const {
    if (const toml::node* n = find(key)) return *n;
    fail_table(path_ + " is missing the required key '" + std::string(key) + "'");
  }
  [[noreturn]] void fail(const toml::node& at, const std::string& msg) const {
    fail_at(file_, at, msg);
  }
  // At the table's header (or its first key when it has no header).
  [[noreturn]] void fail_table(const std::string& msg) const { fail_at(file_, table_, msg); }
  std::string locate(std::string_view key) const {
    return node_location(file_, require(key).source()) + ": " + name(key);
  }

  float number(std::string_view key, const Limit& limit) const {
    return to_number(file_, require(key), name(key), limit);
  }
  float number(std::string_view key, float fallback, const Limit& limit) const {
    return find(key) ? number(key, limit) : fallback;
  }
  vec4 vector(std::string_view key, const Limit& limit) const {
    return to_vector(file_, require(key), name(key), limit);
  }
  vec4 vector(std::string_view key, const vec4& fallback, const Limit& limit) const {
    return find(key) ? vector(key, limit) : fallback;
  }
  // A non-empty string.
  std::string string(std::string_view key) const {
    const toml::node& n = require(key);
    const auto* s = n.as_string();
    if (!s) fail(n, name(key) + " must be a string (got " + type_name(n) + ")");
    if (s->get().empty()) fail(n, name(key) + " must not be empty");
    return s->get();
  }
  Reader table(std::string_view key, std::initializer_list<std::string_view> keys) const {
    const toml::node& n = require(key);
    const toml::table* t = n.as_table();
    if (!t) fail(n, name(key) + " must be a table (got " + type_name(n) + ")");
    return Reader(file_, *t, name(key), keys);
  }

 private:
  const std::string& file_;
  const toml::table& table_;
  std::string path_;
};

}  // namespace rt2::io
