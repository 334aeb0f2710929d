// rt2cpr/failure.cpp — a failure as one line (see failure.h).
#include "rt2cpr/failure.h"

#include <cstdio>
#include <exception>
#include <new>

#include "rt2/base/error.h"

namespace rt2cpr {

std::string printable(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  char buf[8];
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    const auto next = i + 1 < text.size() ? static_cast<unsigned char>(text[i + 1]) : 0;
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c < 0x20 || c == 0x7f) {
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    } else if (c == 0xc2 && next >= 0x80 && next <= 0x9f) {
      std::snprintf(buf, sizeof buf, "\\u%04x", next);
      out += buf;
      ++i;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out;
}

std::string failure_message(const char* doing) noexcept {
  // "out of memory" fits std::string's inline buffer: returning it allocates nothing.
  try {
    try {
      throw;
    } catch (const rt2::Error& e) {
      return printable(e.what());
    } catch (const std::bad_alloc&) {
      return doing ? "out of memory while " + printable(doing) : "out of memory";
    } catch (const std::exception& e) {
      return "internal error: " + printable(e.what());
    } catch (...) {
      return "internal error: an unknown exception";
    }
  } catch (...) {
    return "out of memory";
  }
}

}  // namespace rt2cpr
