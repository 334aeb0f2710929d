// rt2/lights/morton.h — 30-bit Morton codes of points in a box: the sort key of a light BVH
// rebuilt every frame from sorted codes (Karras, "Maximizing Parallelism in the
// Construction of BVHs, Octrees, and k-d Trees", HPG 2012; the same 10 bits per axis).
//
// The box is cut into 1024 cells per axis and the cell indices x, y, z (10 bits each) are
// interleaved from the top, x first (bit 3i + 2 is bit i of x; bits 30 and 31 are 0):
//   bit  29 28 27  26 25 24  ...   2  1  0
//        x9 y9 z9  x8 y8 z8  ...  x0 y0 z0
// Sorting the codes orders the points along a Z-order curve: points that share the top 3k
// bits lie in the same cell of the k-times-halved box.
#pragma once

#include <cstdint>

#include "rt2/geometry/aabb.h"

namespace rt2 {

// Spreads the low 10 bits of v two zero bits apart: bit i goes to bit 3i (i < 10), every
// other bit of the result is 0. Bits 10 and up of v are ignored.
constexpr std::uint32_t expand_bits_10(std::uint32_t v) {
  v &= 0x3ffu;
  v = (v | (v << 16)) & 0x030000ffu;  // bits at 24-25 | 0-7
  v = (v | (v << 8)) & 0x0300f00fu;   // 24-25 | 12-15 | 0-3
  v = (v | (v << 4)) & 0x030c30c3u;   // 24-25 | 18-19 | 12-13 | 6-7 | 0-1
  v = (v | (v << 2)) & 0x09249249u;   // 27 | 24 | ... | 3 | 0
  return v;
}

namespace detail {

// The cell index 0 ... 1023 of coordinate c along an axis from lo of width extent:
// clamp(int((c - lo) / extent * 1024), 0, 1023), computed in float as written. The float
// is tested before it is converted, because converting NaN or a float beyond the int range
// is undefined behaviour in C++: a flat axis (extent 0), an empty or NaN box (extent not
// > 0) and a NaN coordinate give 0; -inf and anything left of lo give 0; +inf and anything
// at or right of hi give 1023. A box wider than FLT_MAX has extent +inf, so every point
// lands in cell 0 of that axis. Monotone non-decreasing in c (rounding is monotone).
inline std::uint32_t morton_cell(float c, float lo, float extent) {
  if (!(extent > 0.0f)) return 0;
  const float t = (c - lo) / extent * 1024.0f;
  if (!(t > 0.0f)) return 0;  // NaN as well
  if (t >= 1023.0f) return 1023;
  return static_cast<std::uint32_t>(t);  // 0 < t < 1023: exact truncation, no UB
}

}  // namespace detail

// The Morton codes of many points in one box: morton_code with the division by the extent
// made a multiplication by 1024 / extent, computed once (the cells can differ from
// morton_code's by rounding at their borders; the order stays monotone along each axis).
class MortonGrid {
 public:
  explicit MortonGrid(const Aabb& bounds) : lo_(bounds.lo) {
    const vec4 extent = bounds.extent();
    for (int a = 0; a < 3; ++a) scale_[a] = extent[a] > 0.0f ? 1024.0f / extent[a] : 0.0f;
  }
  std::uint32_t code(const vec4& p) const {
    return expand_bits_10(cell(p[0], 0)) << 2 | expand_bits_10(cell(p[1], 1)) << 1 |
           expand_bits_10(cell(p[2], 2));
  }

 private:
  // As detail::morton_cell: tested before the conversion (NaN, infinities, outside the box).
  std::uint32_t cell(float c, int axis) const {
    const float t = (c - lo_[axis]) * scale_[axis];
    if (!(t > 0.0f)) return 0;
    if (t >= 1023.0f) return 1023;
    return static_cast<std::uint32_t>(t);
  }
  vec4 lo_;
  float scale_[3];
};

// The 30-bit Morton code of p (lanes x y z; w ignored) in 1024 cells per axis of `bounds`,
// laid out as above. Points outside the box clamp to its edge cells; see detail::morton_cell
// for flat axes, NaN and infinities (never undefined behaviour).
inline std::uint32_t morton_code(const vec4& p, const Aabb& bounds) {
  const vec4 extent = bounds.extent();
  const std::uint32_t x = detail::morton_cell(p[0], bounds.lo[0], extent[0]);
  const std::uint32_t y = detail::morton_cell(p[1], bounds.lo[1], extent[1]);
  const std::uint32_t z = detail::morton_cell(p[2], bounds.lo[2], extent[2]);
  return expand_bits_10(x) << 2 | expand_bits_10(y) << 1 | expand_bits_10(z);
}

}  // namespace rt2
