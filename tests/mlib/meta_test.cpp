// mlib/meta.h: compile-time factorial and integer square root.
#include "mlib/meta.h"

#include <gtest/gtest.h>

#include <cmath>

namespace mlib {
namespace {

TEST(Meta, FactorialIsComputedAtCompileTime) {
  static_assert(Factorial<0>::value == 1);
  static_assert(Factorial<7>::value == 5040);  // the thesis's example
  static_assert(Factorial<20>::value == 2432902008176640000ull);
  std::uint64_t f = 1;
  for (unsigned n = 1; n <= 20; ++n) {
    f *= n;
    EXPECT_EQ(factorial(n), f);
  }
}

TEST(Meta, IsqrtIsTheFloorOfTheSquareRootForEveryInput) {
  static_assert(Root<10>::value == 3);
  static_assert(Root<16>::value == 4);
  static_assert(isqrt(0) == 0 && isqrt(1) == 1 && isqrt(2) == 1);
  static_assert(isqrt(~0ull) == 4294967295ull);
  for (std::uint64_t n = 0; n < 100000; ++n) {
    const std::uint64_t r = isqrt(n);
    ASSERT_LE(r * r, n);
    ASSERT_GT((r + 1) * (r + 1), n);
  }
  for (std::uint64_t r : {65535ull, 65536ull, 3037000499ull, 4294967295ull}) {
    EXPECT_EQ(isqrt(r * r), r);
    if (r < 4294967295ull) {
      EXPECT_EQ(isqrt(r * r - 1), r - 1);
    }
  }
}

}  // namespace
}  // namespace mlib
