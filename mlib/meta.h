// mlib/meta.h — small compile-time helpers (thesis 4.1.2–4.1.3), written correctly.
//
// The thesis shows template recursion for N! and an integer square root found by binary
// search between Low and Upp; its listings have typos (`calcc`, `template <7>`). Here the
// same ideas are constexpr functions, with the class-template forms kept as thin wrappers
// for code that wants a type.
#pragma once

#include <cstdint>

namespace mlib {

// n! for n <= 20 (20! is the largest factorial that fits in 64 bits).
constexpr std::uint64_t factorial(unsigned n) {
  std::uint64_t r = 1;
  for (unsigned k = 2; k <= n; ++k) r *= k;
  return r;
}

// floor(sqrt(n)), exact for every 64-bit n: binary search for the largest m with m*m <= n.
constexpr std::uint64_t isqrt(std::uint64_t n) {
  std::uint64_t lo = 0, hi = n < 2 ? n : (n < (1ull << 32) ? n : (1ull << 32) - 1);
  while (lo < hi) {
    const std::uint64_t mid = lo + (hi - lo + 1) / 2;
    if (mid <= n / mid) lo = mid; else hi = mid - 1;
  }
  return lo;
}

template <unsigned N>
struct Factorial {
  static_assert(N <= 20, "N! overflows 64 bits for N > 20");
  static constexpr std::uint64_t value = factorial(N);
};

// The thesis's Root<N>, but rounding down (Root<10> = 3) like isqrt.
template <std::uint64_t N>
struct Root {
  static constexpr std::uint64_t value = isqrt(N);
};

}  // namespace mlib
