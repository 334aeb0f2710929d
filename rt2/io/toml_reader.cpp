// rt2/io/toml_reader.cpp — the TOML value checks behind Reader (internal; see
// rt2/io/toml_reader.h): type names for messages, positions of nodes, and numbers and
// 3-vectors checked to be finite, of bounded magnitude and within their Limit.
#include "rt2/io/toml_reader.h"

#include <cmath>
#include <cstddef>

#include "rt2/base/error.h"

namespace rt2::io {

std::string type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a float";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    default:
      return "nothing";
  }
}

std::string node_location(const std::string& file, const toml::source_region& r) {
  return location(file, r.begin.line, r.begin.column);
}

[[noreturn]] void fail_at(const std::string& file, const toml::node& n, const std::string& msg) {
  throw Error(one_line(node_location(file, n.source()) + ": " + msg));
}

float to_number(const std::string& file, const toml::node& n, const std::string& name,
                const Limit& limit) {
  double v = 0.0;
  if (const auto* i = n.as_integer())
    v = static_cast<double>(i->get());
  else if (const auto* f = n.as_floating_point())
    v = f->get();
  else
    fail_at(file, n, name + " must be a number (got " + type_name(n) + ")");
  if (!std::isfinite(v)) fail_at(file, n, name + " must be a finite number (got " + fmt(v) + ")");
  if (std::fabs(v) > kMaxMagnitude)
    fail_at(file, n,
            name + " is too large: at most " + fmt(kMaxMagnitude) + " in magnitude (got " + fmt(v) +
                ")");
  const auto x = static_cast<float>(v);
  if (!limit.contains(x))
    fail_at(file, n, name + " must be " + limit.text() + " (got " + fmt(v) + ")");
  return x;
}

vec4 to_vector(const std::string& file, const toml::node& n, const std::string& name,
               const Limit& limit) {
  const toml::array* a = n.as_array();
  if (!a) fail_at(file, n, name + " must be an array of 3 numbers (got " + type_name(n) + ")");
  if (a->size() != 3) {
    fail_at(file, n,
            name + " must be an array of 3 numbers (got " + std::to_string(a->size()) +
                (a->size() == 1 ? " element)" : " elements)"));
  }
  float c[3];
  for (std::size_t i = 0; i < 3; ++i)
    c[i] = to_number(file, (*a)[i], name + "[" + std::to_string(i) + "]", limit);
  return vec4(c[0], c[1], c[2]);
}

}  // namespace rt2::io
