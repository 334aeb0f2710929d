// mlib/vec4.cpp — the out-of-line parts of vec4 (formatting).
#include <cstdio>
#include <string>

#include "mlib/vec4_functions.h"

namespace mlib {

std::string str(const vec4& v) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "(%.9g, %.9g, %.9g, %.9g)", static_cast<double>(v[0]),
                static_cast<double>(v[1]), static_cast<double>(v[2]),
                static_cast<double>(v[3]));
  return buf;
}

}  // namespace mlib
