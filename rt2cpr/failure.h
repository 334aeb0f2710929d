// rt2cpr/failure.h — the one line rt2cpr prints for a failure (after "rt2cpr: ").
#pragma once

#include <string>

namespace rt2cpr {

// The exception being handled, as one line: an rt2::Error's message, "out of memory" for
// std::bad_alloc, "internal error: WHAT" for any other exception. Call it only inside a
// catch block.
std::string failure_message();

}  // namespace rt2cpr
