// rt2cpr/failure.cpp — a failure as one line (see failure.h).
#include "rt2cpr/failure.h"

#include <exception>
#include <new>

#include "rt2/base/error.h"

namespace rt2cpr {

std::string failure_message() {
  try {
    throw;
  } catch (const rt2::Error& e) {
    return e.what();
  } catch (const std::bad_alloc&) {
    return "out of memory";
  } catch (const std::exception& e) {
    return std::string("internal error: ") + e.what();
  } catch (...) {
    return "internal error: an unknown exception";
  }
}

}  // namespace rt2cpr
