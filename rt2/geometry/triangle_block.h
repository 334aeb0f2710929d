// rt2/geometry/triangle_block.h — four triangles stored as structure of arrays, the leaf
// data of the wide BVH, so that one SIMD pass tests a ray against all four.
//
// Each triangle keeps its vertices exactly as given (the watertight test needs the shared
// bits of shared vertices) and its normal N = E2 x E1, as rt2::Triangle holds them, so the
// block tests compute the same values as the one-triangle tests of triangle.h, bit for bit.
// The fast test reads N rather than recomputing it (as Embree's Triangle4 does): more bytes
// per block, fewer operations on the path each ray waits on. A lane without a triangle holds
// NaN (no ray hits it) and prim kNoPrim. A leaf is a run of consecutive blocks, the last with
// kLastBlock set in prim[0]. The tests (rt2/kernel/) are compiled per instruction set.
#pragma once

#include <cstdint>
#include <limits>

#include "mlib/huge_pages.h"
#include "rt2/geometry/triangle.h"

namespace rt2 {

// 208 bytes, aligned to 16 so that a block spans at most 4 cache lines: 12 rows of 4
// floats (V0, V1, V2, N; x y z each) and 4 triangle indices.
struct alignas(16) TriangleBlock {
  static constexpr int kLanes = 4;
  static constexpr std::uint32_t kNoPrim = 0x7fffffffu;
  static constexpr std::uint32_t kLastBlock = 0x80000000u;  // in prim[0]

  float v0[3][kLanes], v1[3][kLanes], v2[3][kLanes], n[3][kLanes];  // [axis][lane]
  std::uint32_t prim[kLanes];  // index into Accel::tris, or kNoPrim

  // A block of empty lanes.
  static TriangleBlock empty() {
    TriangleBlock b;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (int a = 0; a < 3; ++a)
      for (int l = 0; l < kLanes; ++l) b.v0[a][l] = b.v1[a][l] = b.v2[a][l] = b.n[a][l] = nan;
    for (std::uint32_t& p : b.prim) p = kNoPrim;
    return b;
  }
  void set(int lane, const Triangle& t, std::uint32_t index) {
    for (int a = 0; a < 3; ++a) {
      v0[a][lane] = t.v0[a];
      v1[a][lane] = t.v1[a];
      v2[a][lane] = t.v2[a];
      n[a][lane] = t.n[a];
    }
    prim[lane] = (prim[lane] & kLastBlock) | index;
  }
  std::uint32_t prim_of(int lane) const { return prim[lane] & ~kLastBlock; }
  bool last() const { return (prim[0] & kLastBlock) != 0; }
};
static_assert(sizeof(TriangleBlock) == 208);

// A tree's leaf blocks, on huge pages once large (mlib/huge_pages.h): a ray reads a few
// blocks anywhere in the array. resize leaves the new blocks unwritten, for the builder's
// threads to fill.
using TriangleBlocks = mlib::HugePageBuffer<TriangleBlock>;

}  // namespace rt2
