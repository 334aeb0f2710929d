// rt2/geometry/triangle_block.h — four triangles stored as structure of arrays, the leaf
// data of the wide BVH, so that one SIMD pass tests a ray against all four.
//
// Each triangle keeps its vertices exactly as given (the watertight test needs the shared
// bits of shared vertices), as rt2::Triangle holds them; the fast test recomputes the
// normal N = E2 x E1 with the operations Triangle::make uses, so the block tests compute
// the same values as the one-triangle tests of triangle.h, bit for bit. (Storing N would
// cost 48 more bytes per block, and a ray's time goes to waiting for memory, not to nine
// multiplies: measured, the smaller block is faster.) A lane without a triangle holds NaN coordinates (no
// ray hits it) and prim kNoPrim. A leaf of the BVH is a run of consecutive blocks; the
// last one has kLastBlock set in prim[0].
//
// The tests themselves (triangle_block_intersect.h) are compiled per instruction set.
#pragma once

#include <cstdint>
#include <limits>

#include "rt2/geometry/triangle.h"

namespace rt2 {

// 160 bytes, aligned to 32 so that a block always spans 3 cache lines: 9 rows of 4 floats
// (V0, V1, V2; x y z each) and 4 triangle indices.
struct alignas(32) TriangleBlock {
  static constexpr int kLanes = 4;
  static constexpr std::uint32_t kNoPrim = 0x7fffffffu;
  static constexpr std::uint32_t kLastBlock = 0x80000000u;  // in prim[0]

  float v0[3][kLanes], v1[3][kLanes], v2[3][kLanes];  // [axis][lane]
  std::uint32_t prim[kLanes];  // index into Accel::tris, or kNoPrim

  // A block of empty lanes.
  static TriangleBlock empty() {
    TriangleBlock b;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (int a = 0; a < 3; ++a)
      for (int l = 0; l < kLanes; ++l) b.v0[a][l] = b.v1[a][l] = b.v2[a][l] = nan;
    for (std::uint32_t& p : b.prim) p = kNoPrim;
    return b;
  }
  void set(int lane, const Triangle& t, std::uint32_t index) {
    for (int a = 0; a < 3; ++a) {
      v0[a][lane] = t.v0[a];
      v1[a][lane] = t.v1[a];
      v2[a][lane] = t.v2[a];
    }
    prim[lane] = (prim[lane] & kLastBlock) | index;
  }
  std::uint32_t prim_of(int lane) const { return prim[lane] & ~kLastBlock; }
  bool last() const { return (prim[0] & kLastBlock) != 0; }
};
static_assert(sizeof(TriangleBlock) == 160);

}  // namespace rt2
