// tests/mlib/reference.h — a plain scalar four-float reference for checking vec4, and
// fixed-seed random inputs.
#pragma once

#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "mlib/vec4_functions.h"

namespace mlib::test {

using Ref = std::array<float, 4>;

inline Ref ref(const vec4& v) { return {v[0], v[1], v[2], v[3]}; }
inline vec4 make(const Ref& r) { return vec4(r[0], r[1], r[2], r[3]); }

// Bitwise equality of floats (distinguishes -0 from +0, NaN payloads equal to themselves).
inline bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// n fixed-seed random vectors with components log-uniform in magnitude over
// [1e-3, 1e3] and random sign, so products and sums stay finite and normal.
inline std::vector<Ref> random_refs(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> expo(-3.0f, 3.0f);
  std::bernoulli_distribution sign(0.5);
  std::vector<Ref> out(n);
  for (auto& r : out)
    for (float& c : r) c = (sign(rng) ? -1.0f : 1.0f) * std::pow(10.0f, expo(rng));
  return out;
}

// The dot product in double, and the bound |error| <= 4 eps sum |a_i b_i| that a float
// evaluation in any summation order satisfies.
inline double dot_ref(const Ref& a, const Ref& b) {
  double s = 0;
  for (int i = 0; i < 4; ++i) s += double(a[i]) * double(b[i]);
  return s;
}
inline double dot_bound(const Ref& a, const Ref& b) {
  double s = 0;
  for (int i = 0; i < 4; ++i) s += std::fabs(double(a[i]) * double(b[i]));
  return 4.0 * 1.1920929e-7 * s;
}

}  // namespace mlib::test
