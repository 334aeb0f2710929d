// tests/rt2/error_of.h — the message of the rt2::Error a piece of code throws, for tests that
// check what a failure says.
#pragma once

#include <gtest/gtest.h>

#include <exception>
#include <string>

#include "rt2/base/error.h"

namespace rt2::test {

// The message of the rt2::Error that `f` throws; a test failure if it throws nothing or
// anything else.
template <class F>
inline std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "threw something other than rt2::Error: " << e.what();
    return {};
  } catch (...) {
    ADD_FAILURE() << "threw something other than rt2::Error";
    return {};
  }
  ADD_FAILURE() << "threw nothing";
  return {};
}

}  // namespace rt2::test
