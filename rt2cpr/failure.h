// rt2cpr/failure.h — the one line rt2cpr prints for a failure (after "rt2cpr: "), and text
// made safe to print as part of one line.
#pragma once

#include <string>
#include <string_view>

namespace rt2cpr {

// `text` with every control character escaped, so that it prints as one line and cannot
// drive a terminal: \n, \r and \t as such, other C0 characters and DEL as \xHH, C1
// characters (UTF-8 U+0080 ... U+009F) as \uHHHH. Other bytes, valid UTF-8 or not, stay.
std::string printable(std::string_view text);

// The exception being handled, as one printable line: an rt2::Error's message, "out of
// memory" for std::bad_alloc (" while DOING" when `doing` is given), "internal error: WHAT"
// for any other exception. Call it only inside a catch block. Never throws: short of memory
// to build the message, it returns "out of memory".
std::string failure_message(const char* doing = nullptr) noexcept;

}  // namespace rt2cpr
