// rt2/render/supersampling.cpp — the grid and circle subpixel patterns.
#include "rt2/render/supersampling.h"

#include <cmath>
#include <numbers>

#include "rt2/base/error.h"

namespace rt2 {

std::vector<SubpixelOffset> subpixel_offsets(int n, Pattern pattern) {
  if (n < 1) throw Error("subpixels must be >= 1, got " + std::to_string(n));
  std::vector<SubpixelOffset> out;
  out.reserve(static_cast<std::size_t>(n));
  if (n == 1) {
    out.push_back({0.5f, 0.5f});
    return out;
  }
  if (pattern == Pattern::grid) {
    // Row i holds samples [first, last); its height is (last - first) / N, so every sample
    // sits at the centre of a cell of area 1/N and the samples' mean is the pixel centre.
    const int rows = static_cast<int>(std::floor(std::sqrt(double(n))));
    for (int i = 0; i < rows; ++i) {
      const long long first = static_cast<long long>(n) * i / rows;
      const long long last = static_cast<long long>(n) * (i + 1) / rows;
      const int in_row = static_cast<int>(last - first);
      const float y = static_cast<float>(double(first + last) / (2.0 * n));
      for (int j = 0; j < in_row; ++j) out.push_back({(float(j) + 0.5f) / float(in_row), y});
    }
    return out;
  }
  // Angles theta_k = 2 pi k / N + phi. Two samples share an x when theta_j = -theta_k
  // (mod 2 pi), i.e. 2 phi = -2 pi (j + k) / N (mod 2 pi); they share a y when
  // theta_j = pi - theta_k. With phi = pi / (4N) both need (1/2 + 2 (j + k)) / N to be an
  // integer (resp. odd integer), which it never is: all x and all y are distinct.
  const double radius = std::sqrt(1.0 / 6.0);
  const double phi = std::numbers::pi / (4.0 * n);
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * std::numbers::pi * k / n + phi;
    out.push_back({static_cast<float>(0.5 + radius * std::cos(a)),
                   static_cast<float>(0.5 + radius * std::sin(a))});
  }
  return out;
}

const char* pattern_name(Pattern p) { return p == Pattern::grid ? "grid" : "circle"; }

Pattern parse_pattern(const std::string& name) {
  if (name == "grid") return Pattern::grid;
  if (name == "circle") return Pattern::circle;
  throw Error("unknown subpixel pattern '" + name + "' (expected grid or circle)");
}

}  // namespace rt2
