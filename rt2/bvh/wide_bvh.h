// rt2/bvh/wide_bvh.h — the wide BVH rt2 traces: nodes of N = 4, 8 or 16 children whose boxes
// are stored as structure of arrays, so one SIMD pass tests a ray against all of them (Wald
// et al. 2008, "Getting Rid of Packets"; Embree's BVH4/BVH8; 16 children for AVX-512 as in
// Fuetterling et al. 2017), with leaves of triangle blocks (rt2/geometry/triangle_block.h).
//
// Collapsed from the binary SAH tree (bvh/build.h): each wide node holds a cut of its binary
// node's subtree into at most N slots, chosen by dynamic programming so that the sum of the
// wide nodes' areas is least (Ylitie et al. 2017; wide_build.cpp). The binary tree's leaves
// and padded boxes (build.cpp) are kept, so the thesis's max-leaf-size rule still holds.
// The nodes' boxes are floats (WideNode), or on request quantized to 8 bits (QuantizedNode).
// Plain data; the builder makes it, the traversal (rt2/kernel/wide_traverse.h) reads it.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "mlib/huge_pages.h"
#include "rt2/geometry/aabb.h"
#include "rt2/bvh/node.h"
#include "rt2/geometry/triangle_block.h"

namespace rt2 {

// A child reference: an inner node's index, or kLeaf | the index of the leaf's first block.
inline constexpr std::uint32_t kLeaf = 0x80000000u;
inline constexpr std::uint32_t kNoChild = 0xffffffffu;  // an empty tree's root

// N = 4: 96 bytes of bounds + 16 of children + 16 of orders = 128 (two cache lines).
// N = 8: 192 + 32 + 32 = 256 (four lines). N = 16: 384 + 64 + 64 = 512 (eight lines).
// An unused slot has the empty box lo = +inf, hi = -inf, which no ray enters (not even one
// with a zero direction component: the slab distances are infinite, never NaN).
template <int N>
struct alignas(64) WideNode {
  // Rows: lo x, hi x, lo y, hi y, lo z, hi z; row 2a + 1 is the high side of axis a, so a
  // ray picks its near row per axis as 2a + (direction < 0) and its far row as near ^ 1.
  float bounds[6][N];
  std::uint32_t child[N];
  // The children along each direction octant's diagonal: bits [b o, b o + b) of
  // octant_order[j], b = kOrderBits<N>, name the slot at position j for octant o, the children
  // sorted by their boxes' centres along the diagonal, farthest first, then the unused slots.
  // Octant o has bit a set when the direction's component a is negative (as the near rows
  // above). The 8- and 16-wide walks push the children a ray enters in this order, so that the
  // nearest ends on top, without sorting them by distance (Fuetterling et al. 2017,
  // "Accelerated Single Ray Tracing for Wide Vector Units"); the 4-wide walk sorts, and leaves
  // it unread.
  std::uint32_t octant_order[N];

  // The used slots, [0, slots()): the build fills them first.
  int slots() const {
    int n = 0;
    while (n < N && bounds[0][n] <= bounds[1][n]) ++n;
    return n;
  }
  float plane(int row, int i) const { return bounds[row][i]; }
  Aabb box(int i) const {
    return {vec4(bounds[0][i], bounds[2][i], bounds[4][i]),
            vec4(bounds[1][i], bounds[3][i], bounds[5][i])};
  }
};
static_assert(sizeof(WideNode<4>) == 128 && sizeof(WideNode<8>) == 256 &&
              sizeof(WideNode<16>) == 512);

// QuantizedNode: WideNode with its child boxes quantized (Ylitie et al. 2017; Embree's
// compressed nodes): plane (row r, slot i) = origin[r] + q[r][i] * scale(r / 2), scale(a) =
// 2^(scale_bits[a] - 127) in [2^-126, 2^120]. The product of an 8-bit integer and such a
// power of two is exact, so the sum is rounded once whether it is fused or not; the origins
// are multiples of 2^-126, so no plane is a denormal that flushing (FTZ / DAZ) would move:
// the builder and every kernel decode the same float. The builder rounds each plane outward
// (a decoded box holds the child's padded box, bvh/build.cpp), so no ray misses a box it
// would have entered before quantization. An axis whose boxes span more than 255 * 2^120 gets
// origins -inf (low rows) and +inf (high rows), every child unbounded along it. Unused slots
// are those outside `used`: the walks drop them from every test's result, whatever their rows
// decode to. Fewer bytes than a WideNode, for a few more operations per node test
// (wide_traverse.h: node_row).
// N = 4: 32 bytes of header + 24 of planes + 16 of children + 16 of orders = 88, padded to 96.
// N = 8: 32 + 48 + 32 + 32 = 144. N = 16: 32 + 96 + 64 + 64 = 256 (four cache lines).
template <int N>
struct alignas(N >= 16 ? 64 : 16) QuantizedNode {
  float origin[6];                // per row
  std::uint8_t scale_bits[3];     // per axis: the scale's float exponent bits
  std::uint8_t count;             // the used slots are [0, count)
  std::uint32_t used;             // (1 << count) - 1
  std::uint8_t q[6][N];           // rows as WideNode::bounds
  std::uint32_t child[N];         // as WideNode's
  std::uint32_t octant_order[N];  // as WideNode's, from the boxes before quantization

  int slots() const { return count; }

  float scale(int axis) const {
    return std::bit_cast<float>(std::uint32_t(scale_bits[axis]) << 23);
  }
  // The plane of row `row`, slot i, as the walks decode it.
  float plane(int row, int i) const { return origin[row] + float(q[row][i]) * scale(row >> 1); }
  // Slot i's box as decoded.
  Aabb box(int i) const {
    return {vec4(plane(0, i), plane(2, i), plane(4, i)),
            vec4(plane(1, i), plane(3, i), plane(5, i))};
  }
};
static_assert(sizeof(QuantizedNode<4>) == 96 && sizeof(QuantizedNode<8>) == 144 &&
              sizeof(QuantizedNode<16>) == 256);

// Sets node's boxes to boxes[0 .. n) (n <= N), each rounded outward to the quantized planes
// the node can hold, and its used slots to [0, n).
template <int N>
void quantize_boxes(QuantizedNode<N>& node, const Aabb* boxes, int n);

// Bits per octant in WideNode::octant_order: enough for a slot index (8 octants x 4 bits
// fill the 32 of a 16-wide node's orders).
template <int N>
inline constexpr int kOrderBits = N <= 8 ? 3 : 4;

template <int N>
struct WideBvh {
  // The nodes, of one layout: `quantized_nodes` when `quantized`, else `nodes` (NodeLayout).
  // Depth first; the first is the root when root is not a leaf. On huge pages once large
  // (mlib/huge_pages.h): a ray reads a few nodes anywhere in the array.
  mlib::HugePageBuffer<WideNode<N>> nodes;
  mlib::HugePageBuffer<QuantizedNode<N>> quantized_nodes;
  bool quantized = false;
  std::uint32_t root = kNoChild;   // 0, a leaf (a tree of one leaf), or kNoChild (no triangles)
  // The binary tree's root box (padded, build.cpp), which holds every triangle: a ray that
  // misses it (slab_entry, as the binary tree's walk tests it) hits no triangle, and the
  // closest-hit walk returns before its per-ray set-up (rt2/kernel/wide_traverse.h, may_enter).
  Aabb bounds;
  std::uint32_t leaves = 0;
  std::uint32_t max_depth = 0;
  // Whether the closest-hit walk prefetches every child it pushes, not only the one it goes
  // to next: set by collapse_bvh when nodes and blocks together reach kPrefetchPushedBytes.
  // In a tree far larger than the caches most pushed children are fetched from memory, and
  // asking for all of them at once overlaps the waits; in a tree the L2 holds, the extra
  // prefetches only cost.
  bool prefetch_pushed = false;

  // f(nodes) with a pointer to the tree's nodes, of either layout.
  template <class F>
  decltype(auto) with_nodes(F&& f) const {
    return quantized ? f(quantized_nodes.data()) : f(nodes.data());
  }
  std::size_t node_count() const { return quantized ? quantized_nodes.size() : nodes.size(); }
  std::size_t node_bytes() const {
    return quantized ? quantized_nodes.size() * sizeof(QuantizedNode<N>)
                     : nodes.size() * sizeof(WideNode<N>);
  }
};

// The tree size from which collapse_bvh sets WideBvh::prefetch_pushed.
inline constexpr std::size_t kPrefetchPushedBytes = std::size_t(16) << 20;

// What walks of the tree did, for benchmarks and --stats: inner nodes visited (a packet's
// frustum test of a node counts once), leaf blocks tested (four triangles each, per ray),
// and the walks made as packets (rt2/kernel/packet_traverse.h) with the rays they carried.
struct TraversalCounts {
  std::uint64_t nodes = 0, blocks = 0;
  std::uint64_t packets = 0, packet_rays = 0;
  TraversalCounts& operator+=(const TraversalCounts& o) {
    nodes += o.nodes;
    blocks += o.blocks;
    packets += o.packets;
    packet_rays += o.packet_rays;
    return *this;
  }
};

// The tree's cost by the surface area heuristic, as Embree's statistics state it
// (kernels/bvh/bvh_statistics.cpp; Embree prints it after a build with `verbose=3`), so the
// two trees can be compared: for a random line through the root's box, `nodes` is the
// expected number of inner nodes whose boxes it enters (each inner node's surface area
// over the root's, the root's own 1 included) and `leaves` the expected number of triangle
// blocks it would test (each leaf's area ratio times its blocks). By Cauchy's formula, a
// random line that meets a convex body meets a convex body inside it with probability the
// ratio of their surface areas. The root's box is the union of its children's; a tree of
// one leaf has nodes = 0, leaves = its blocks.
struct WideSah {
  double nodes = 0.0, leaves = 0.0;
};

template <int N>
WideSah wide_sah(const WideBvh<N>& bvh, const TriangleBlock* blocks);

// Collapses the binary tree `bvh` over triangles into a wide one: the binary leaf
// [first, first + count) holds triangles[bvh.order[first .. first + count)]. Appends the
// leaves' blocks to `blocks` (prim = index into `triangles`).
template <int N>
WideBvh<N> collapse_bvh(const Bvh& bvh, std::span<const Triangle> triangles,
                        TriangleBlocks& blocks, NodeLayout layout = NodeLayout::plain);

// Refits `bvh`, whose blocks are in `blocks`, to `triangles` moved (the same triangles, by
// the index the blocks hold, at new positions): the blocks take their triangles' vertices and
// normals again and every box is remade bottom up as the build makes it from the same
// triangles in the same nodes (so a tree refit to unmoved triangles is the tree built). The
// shape and the children's octant orders are kept: boxes that grew apart overlap, and the
// tree's SAH cost (wide_sah) grows.
// With `threads` OpenMP threads (<= 0: all).
template <int N>
void refit_bvh(WideBvh<N>& bvh, std::span<const Triangle> triangles, TriangleBlocks& blocks,
               int threads);

}  // namespace rt2
