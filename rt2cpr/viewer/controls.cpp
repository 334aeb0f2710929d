// rt2cpr/viewer/controls.cpp — settings by name, checked as the command line checks them.
#include "rt2cpr/viewer/controls.h"

#include <cstdlib>

#include "rt2/base/error.h"
#include "rt2/render/supersampling.h"

namespace rt2cpr::viewer {

namespace {

long long integer(const std::string& name, const std::string& v, long long lo, long long hi) {
  char* end = nullptr;
  const long long n = std::strtoll(v.c_str(), &end, 10);
  if (v.empty() || end != v.c_str() + v.size() || n < lo || n > hi)
    throw rt2::Error(name + " must be an integer in [" + std::to_string(lo) + ", " +
                     std::to_string(hi) + "], got '" + v + "'");
  return n;
}

}  // namespace

void set_control(Controls& c, const std::string& name, const std::string& value) {
  Controls n = c;
  if (name == "depth") {
    n.settings.depth = int(integer(name, value, 0, 1'000'000));
  } else if (name == "min-weight") {
    char* end = nullptr;
    const float w = std::strtof(value.c_str(), &end);
    if (value.empty() || end != value.c_str() + value.size() || !(w >= 0.0f && w <= 1.0f))
      throw rt2::Error("min-weight must be a number in [0, 1], got '" + value + "'");
    n.settings.min_weight = w;
  } else if (name == "subpixels") {
    n.settings.subpixels = int(integer(name, value, 1, 65536));
    n.settings.passes = 1;
  } else if (name == "pattern") {
    n.settings.pattern = rt2::parse_pattern(value);
  } else if (name == "lights") {
    n.lights = int(integer(name, value, 0, 1'000'000));
  } else if (name == "triangle-test") {
    if (value != "fast" && value != "watertight")
      throw rt2::Error("unknown triangle test '" + value + "' (expected fast or watertight)");
    n.settings.watertight = value == "watertight";
  } else if (name == "threads") {
    n.schedule.threads = int(integer(name, value, 1, 1024));
  } else if (name == "backend") {
    n.schedule.backend = rt2::parse_backend(value);
  } else if (name == "overlay") {
    if (value != "on" && value != "off")
      throw rt2::Error("overlay must be on or off, got '" + value + "'");
    n.overlay = value == "on";
  } else {
    throw rt2::Error("unknown setting '" + name + "' (expected depth, min-weight, subpixels, "
                     "pattern, lights, triangle-test, threads, backend or overlay)");
  }
  n.settings.validate();
  c = n;
}

}  // namespace rt2cpr::viewer
