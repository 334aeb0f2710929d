// rt2/base/error.h — the one exception type of rt2: a complete one-line message for the user.
//
// Loaders and validators throw Error with the file (and line) and the offending field and
// value in the message; rt2cpr prints what() on one line and exits non-zero. Nothing in
// the per-pixel loop throws.
#pragma once

#include <stdexcept>
#include <string>

namespace rt2 {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace rt2
