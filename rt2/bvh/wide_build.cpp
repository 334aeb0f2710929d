// rt2/bvh/wide_build.cpp — collapsing the binary tree into the wide one (see wide_bvh.h).
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>

#include <omp.h>

#include "mlib/fpmode.h"
#include "rt2/bvh/build.h"
#include "rt2/bvh/wide_bvh.h"

namespace rt2 {

namespace {

constexpr int kMinScaleExponent = -126, kMaxScaleExponent = 120;  // see QuantizedNode

// x, or the nearest multiple of 2^-126 below it when |x| < 2^-102 (larger floats are such
// multiples already): a quantized node's origin, so that every plane it decodes is 0 or a
// normal float, and flushing denormals (FTZ / DAZ, which the renderer sets) changes none.
// A denormal x is read by its bits: under DAZ its arithmetic would see 0.
float origin_below(float x) {
  const std::uint32_t bits = std::bit_cast<std::uint32_t>(x);
  if ((bits << 1) == 0) return x;  // +-0
  if ((bits & 0x7f800000u) == 0) return bits >> 31 ? -0x1p-126f : 0.0f;
  if (!(std::fabs(x) < 0x1p-102f)) return x;
  return float(std::floor(double(x) * 0x1p126) * 0x1p-126);
}

// Axis a of the boxes in node's slots [0, n): origins, scale and the planes, each plane the
// nearest the node can hold on the outer side of the box's.
template <int N>
void quantize_axis(QuantizedNode<N>& node, const Aabb* boxes, int n, int a) {
  float lo = std::numeric_limits<float>::infinity(), hi = -lo;
  for (int i = 0; i < n; ++i) {
    lo = std::min(lo, boxes[i].lo[a]);
    hi = std::max(hi, boxes[i].hi[a]);
  }
  lo = origin_below(lo);
  std::uint8_t* qlo = node.q[2 * a];
  std::uint8_t* qhi = node.q[2 * a + 1];
  // The least scale 2^e with lo + 255 * 2^e >= hi, rounded as the walks round it.
  int e = kMinScaleExponent;
  const bool finite = std::isfinite(lo) && std::isfinite(hi);
  if (finite && hi > lo) {
    std::frexp((double(hi) - double(lo)) / 255.0, &e);  // 2^e >= the span / 255
    e = std::clamp(e - 1, kMinScaleExponent, kMaxScaleExponent + 1);
  }
  const auto fits = [&](int x) {
    return lo + 255.0f * std::ldexp(1.0f, x) >= hi;  // the product is exact
  };
  while (finite && e <= kMaxScaleExponent && !fits(e)) ++e;
  if (!finite || e > kMaxScaleExponent) {  // unbounded along this axis (see WideNode)
    node.origin[2 * a] = -std::numeric_limits<float>::infinity();
    node.origin[2 * a + 1] = std::numeric_limits<float>::infinity();
    node.scale_bits[a] = 127;
    for (int i = 0; i < N; ++i) qlo[i] = qhi[i] = 0;
    return;
  }
  node.origin[2 * a] = node.origin[2 * a + 1] = lo;
  node.scale_bits[a] = std::uint8_t(e + 127);
  const float s = node.scale(a);
  const double inv = 1.0 / double(s);
  const auto plane = [&](int q) { return lo + float(q) * s; };
  for (int i = 0; i < n; ++i) {
    // From the nearest estimate, moved until the plane is outside the box and the next
    // one inward is not: bounded steps, since plane(0) = lo and plane(255) >= hi.
    // (fmax: a NaN estimate starts at 0)
    const double l0 = std::floor((double(boxes[i].lo[a]) - lo) * inv);
    const double h0 = std::ceil((double(boxes[i].hi[a]) - lo) * inv);
    int l = int(std::clamp(std::fmax(l0, 0.0), 0.0, 255.0));
    while (l > 0 && plane(l) > boxes[i].lo[a]) --l;
    while (l < 255 && plane(l + 1) <= boxes[i].lo[a]) ++l;
    int h = int(std::clamp(std::fmax(h0, 0.0), 0.0, 255.0));
    while (h < 255 && plane(h) < boxes[i].hi[a]) ++h;
    while (h > 0 && plane(h - 1) >= boxes[i].hi[a]) --h;
    qlo[i] = std::uint8_t(l);
    qhi[i] = std::uint8_t(h);
  }
  for (int i = n; i < N; ++i) {  // unused: an inverted box (the walks mask these slots)
    qlo[i] = 255;
    qhi[i] = 0;
  }
}

// A plain node's boxes: boxes[0 .. n) in slots [0, n), the empty box in the others.
template <int N>
void set_boxes(WideNode<N>& node, const Aabb* boxes, int n) {
  for (int i = 0; i < N; ++i)
    for (int a = 0; a < 3; ++a) {
      node.bounds[2 * a][i] = i < n ? boxes[i].lo[a] : std::numeric_limits<float>::infinity();
      node.bounds[2 * a + 1][i] = i < n ? boxes[i].hi[a] : -std::numeric_limits<float>::infinity();
    }
}

template <int N>
void set_boxes(QuantizedNode<N>& node, const Aabb* boxes, int n) {
  quantize_boxes(node, boxes, n);
}

// Refitting: the boxes of a tree whose triangles moved, its shape kept. Each box is what the
// build gives the same triangles in the same node: the union of their vertices, padded by
// box_pad. The children's orders per octant are kept: they steer which child a walk enters
// first, never what it finds, and remaking them would cost a fifth of the refit.
template <int N, class Node>
class Refitter {
 public:
  Refitter(Node* nodes, std::span<const Triangle> tris, TriangleBlocks& blocks)
      : nodes_(nodes), tris_(tris), blocks_(blocks.data()) {}

  // The unpadded box of the triangles under `ref` (a node or a leaf), its nodes refit and
  // its blocks rewritten. Below depth `split_depth` the children are refit as OpenMP tasks.
  Aabb refit(std::uint32_t ref, int split_depth) {
    if (ref & kLeaf) return leaf(ref & ~kLeaf);
    Node& w = nodes_[ref];
    Aabb child[N];
    const int n = w.slots();
    for (int i = 0; i < n; ++i) {
      const std::uint32_t c = w.child[i];
      if (split_depth > 0) {
#pragma omp task shared(child) firstprivate(c, i, split_depth) if (!(c & kLeaf))
        child[i] = refit(c, split_depth - 1);
      } else {
        child[i] = refit(c, 0);
      }
    }
    if (split_depth > 0) {
#pragma omp taskwait
    }
    Aabb box, padded[N];
    for (int i = 0; i < n; ++i) {
      box.grow(child[i]);
      for (int a = 0; a < 3; ++a) {
        const float pad = box_pad(child[i].lo[a], child[i].hi[a]);
        padded[i].lo[a] = child[i].lo[a] - pad;
        padded[i].hi[a] = child[i].hi[a] + pad;
      }
    }
    set_boxes(w, padded, n);
    return box;
  }

 private:
  Aabb leaf(std::uint32_t first) {
    Aabb box;
    for (TriangleBlock* b = blocks_ + first;; ++b) {
      for (int l = 0; l < TriangleBlock::kLanes; ++l) {
        const std::uint32_t p = b->prim_of(l);
        if (p == TriangleBlock::kNoPrim) continue;
        const Triangle& t = tris_[p];
        b->set(l, t, p);
        box.grow(t.v0);
        box.grow(t.v1);
        box.grow(t.v2);
      }
      if (b->last()) return box;
    }
  }

  Node* nodes_;
  std::span<const Triangle> tris_;
  TriangleBlock* blocks_;
};

// Binary trees of at least this many nodes are collapsed by the team's threads: planned
// and filled by OpenMP tasks.
constexpr std::size_t kParallelNodes = std::size_t(1) << 17;

template <int N>
class Collapser {
 public:
  // The tree's leaf blocks are appended to `blocks`, sized once for all of them (each
  // growth would copy them all).
  Collapser(const Bvh& bvh, std::span<const Triangle> tris, TriangleBlocks& blocks,
            WideBvh<N>& out)
      : bvh_(bvh), tris_(tris), blocks_(blocks), first_block_(blocks.size()), out_(out) {}

  // The reference for the root: a wide node made from it (nodes[0]), or its leaf.
  std::uint32_t convert_root() {
    Cursor at{1, first_block_};
    Tally tally;
    std::uint32_t root = 0;
    if (bvh_.nodes[0].is_leaf()) {
      blocks_.resize(first_block_ + blocks_of(bvh_.nodes[0]));
      root = leaf(bvh_.nodes[0], at, tally);
    } else {
      choice_.resize(bvh_.nodes.size());  // every entry planned before it is read
      wide_split_.resize(bvh_.nodes.size());
      const bool parallel = bvh_.nodes.size() >= kParallelNodes;
      const unsigned mode = mlib::denormal_mode();
#pragma omp parallel if (parallel)
      {
        const mlib::DenormalModeScope caller_mode(mode);  // the team computes as one thread
#pragma omp single
        plan(0, 0);
      }
      Size sizes[N];  // the root's children's subtrees
      const Size size = wide_size(0, sizes);
      blocks_.resize(first_block_ + size.blocks);
      out_.nodes.resize(size.nodes);  // exactly: no copy to shrink it after
#pragma omp parallel if (parallel)
      {
        const mlib::DenormalModeScope caller_mode(mode);
#pragma omp single
        fill(0, 0, 0, sizes, at, tally);
      }
    }
    out_.leaves = tally.leaves;
    out_.max_depth = tally.max_depth;
    return root;
  }

 private:
  // Where the next wide node and the next leaf block go.
  struct Cursor {
    std::uint32_t node;
    std::size_t block;
  };
  // The wide nodes and leaf blocks of a subtree.
  struct Size {
    std::uint32_t nodes = 0;
    std::size_t blocks = 0;
  };
  // What a subtree's fill adds to the tree's record.
  struct Tally {
    std::uint32_t leaves = 0, max_depth = 0;
  };

  // The fills of subtrees that begin at most this deep are tasks of their own, when their
  // subtree holds kTaskBlocks blocks or more: for N = 16 the root's children (up to 16),
  // for N = 4 and 8 their children too.
  static constexpr std::uint32_t kTaskDepth = N >= 16 ? 1 : 2;
  static constexpr std::size_t kTaskBlocks = 4096;

  // Fills wide node `index` from binary node b (inner), its subtrees' nodes and blocks from
  // `at` on. The node's inner children get consecutive slots, allocated before any of their
  // subtrees, so siblings sit side by side in memory (as Embree's allocator places them): a
  // walk that returns to a sibling finds it near the one it just left. Leaves' blocks
  // likewise follow each other. A subtree filled by a task takes the nodes and blocks that
  // the serial fill would give it (`sizes`: its children's, when known), so the tree is the
  // same at any thread count.
  void fill(std::uint32_t index, std::uint32_t b, std::uint32_t depth, const Size* sizes,
            Cursor& at, Tally& tally) {
    tally.max_depth = std::max(tally.max_depth, depth);
    std::uint32_t kids[N];
    const int n = slots(b, kids);
    WideNode<N> w;
    Aabb boxes[N];
    for (int i = 0; i < N; ++i) w.child[i] = 0;
    for (int i = 0; i < n; ++i) {
      const BvhNode& k = bvh_.nodes[kids[i]];
      boxes[i] = {mlib::load_xyz(k.lo), mlib::load_xyz(k.hi)};
      w.child[i] = k.is_leaf() ? leaf(k, at, tally) : at.node++;
    }
    set_boxes(w, boxes, n);
    set_octant_orders(w, boxes, n);
    out_.nodes[index] = w;
    const bool tasks = depth < kTaskDepth && omp_in_parallel();
    Tally task_tally[N];
    for (int i = 0; i < n; ++i) {
      if (w.child[i] & kLeaf) continue;
      if (tasks) {
        Size grand[N];
        const Size size = sizes ? sizes[i] : wide_size(kids[i], grand);
        if (size.blocks >= kTaskBlocks) {
          const Size* known = sizes ? nullptr : grand;
          Cursor task_at = at;
#pragma omp task default(shared) firstprivate(i, task_at, known, grand)
          fill(w.child[i], kids[i], depth + 1, known ? grand : nullptr, task_at, task_tally[i]);
          at.node += size.nodes - 1;  // the child's own node is allocated above
          at.block += size.blocks;
          continue;
        }
      }
      fill(w.child[i], kids[i], depth + 1, nullptr, at, tally);
    }
    if (tasks) {
#pragma omp taskwait
      for (const Tally& t : task_tally) {
        tally.leaves += t.leaves;
        tally.max_depth = std::max(tally.max_depth, t.max_depth);
      }
    }
  }

  // WideNode::octant_order for the n children in slots [0, n), whose boxes are `boxes`.
  // Each child's position is its rank, counted without a branch (a sort of eight random
  // keys mispredicts about every other comparison). Octant 7 - o is octant o's order
  // reversed (its diagonal is the opposite one). A node of two children keeps the identity
  // order: the walk orders two children by their distances (rt2/kernel/wide_traverse.h).
  static void set_octant_orders(WideNode<N>& w, const Aabb* boxes, int n) {
    for (int j = 0; j < N; ++j)  // j in each field
      w.octant_order[j] = std::uint32_t(j) * (kOrderBits<N> == 3 ? 0x249249u : 0x11111111u);
    if (n <= 2) return;
    for (int j = 0; j < N; ++j) w.octant_order[j] = 0;
    float centre[3][N];  // halves added: lo + hi could overflow to inf (and a key to NaN)
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < n; ++i)
        centre[a][i] = boxes[i].lo[a] * 0.5f + boxes[i].hi[a] * 0.5f;
    for (int o = 0; o < 4; ++o) {
      float key[N];  // along the diagonal: farther is larger
      for (int i = 0; i < n; ++i)
        key[i] = ((o & 1 ? -centre[0][i] : centre[0][i]) + (o & 2 ? -centre[1][i] : centre[1][i])) +
                 (o & 4 ? -centre[2][i] : centre[2][i]);
      std::uint32_t slot_at[N];
      for (int j = 0; j < N; ++j) slot_at[j] = std::uint32_t(j);  // the unused slots stay last
      for (int i = 0; i < n; ++i) {
        int rank = 0;  // the keys before key i: larger, or equal in a lower slot
        for (int j = 0; j < n; ++j) rank += (key[j] > key[i]) | ((key[j] == key[i]) & (j < i));
        slot_at[rank] = std::uint32_t(i);
      }
      for (int j = 0; j < N; ++j) {
        const std::uint32_t backward = j < n ? slot_at[n - 1 - j] : slot_at[j];
        w.octant_order[j] |=
            slot_at[j] << (kOrderBits<N> * o) | backward << (kOrderBits<N> * (7 - o));
      }
    }
  }

  // Which binary nodes become wide nodes, by dynamic programming over the binary tree (Ylitie
  // et al. 2017): the sum of the wide nodes' areas (the surface area heuristic's cost of
  // the inner nodes; the leaves are the binary tree's whatever the choice) is least. The
  // greedy rule of Embree's and tinybvh's converters (open the child of largest area until
  // N are there) fills the top of a subtree and leaves nodes of two or three children below
  // it: more nodes, more bytes per triangle and slower incoherent rays. Costs summed in
  // float may pick, where two plans nearly tie, one a few ulps of the cost above the least.
  // A subtree's costs live only while its parent is planned (the walk is depth first), so what
  // stays is the choice: choice_[m][k] for binary subtree m held in at most k slots of a wide
  // node, the slots the least cost takes (the low kUsedBits) and the slots its first child's
  // subtree takes (the bits above; 0: m itself in one slot, a wide node of its own): 10
  // bytes per binary node for N = 8, where a table of the costs as well would take 55. The top
  // levels' subtrees are planned by OpenMP tasks (plan).
  // One choice: the slots used (up to N) below kUsedBits, the first child's above.
  static constexpr int kUsedBits = N <= 8 ? 4 : 5;
  using Choice = std::conditional_t<N <= 8, std::uint8_t, std::uint16_t>;

  // cost[k]: the least cost of binary subtree m held in at most k slots (k = 1 ... N);
  // leaves: the subtree's leaves, at most N. A subtree of L leaves fills at most L slots, so
  // cost[k] = cost[L] for k > L, and the search below skips the splits that would give a
  // child more slots than it has leaves: their sums are no less than the split's at the
  // bound (the costs do not increase with k), and where one ties, the smallest split is
  // taken as the full search would take it, so the tree is the same. The skip spares the
  // N = 16 build most of the full search's 120 splits per binary node.
  using Costs = std::array<float, N + 1>;
  struct Plan {
    Costs cost;
    int leaves;
  };
  static constexpr std::uint32_t kPlanTaskDepth = 8;  // tasks for subtrees down to here
  Plan plan(std::uint32_t m, std::uint32_t depth) {
    const BvhNode& node = bvh_.nodes[m];
    Plan p{{}, 1};
    Costs& cost = p.cost;
    if (node.is_leaf()) {
      for (int k = 1; k <= N; ++k) choice_[m][k] = 1;
      return p;
    }
    Plan left, right;
    if (depth < kPlanTaskDepth && omp_in_parallel()) {
#pragma omp task default(shared)
      left = plan(m + 1, depth + 1);
      right = plan(node.offset, depth + 1);
#pragma omp taskwait
    } else {
      left = plan(m + 1, depth + 1);
      right = plan(node.offset, depth + 1);
    }
    const Costs &l = left.cost, &r = right.cost;
    p.leaves = std::min(N, left.leaves + right.leaves);
    // The least cost of k slots split between the children, and the first child's share.
    const auto split = [&](int k, int lo, int hi, std::uint8_t& arg) {
      float d = std::numeric_limits<float>::infinity();
      arg = std::uint8_t(lo);
      for (int a = lo; a <= hi; ++a) {
        const float c = l[a] + r[k - a];
        if (c < d) d = c, arg = std::uint8_t(a);
      }
      return d;
    };
    // d[k] for 2 <= k <= leaves (an inner node has two leaves at least); the rest +inf, so
    // that no entry is left unset where g++ cannot see that none is read.
    Costs d;
    d.fill(std::numeric_limits<float>::infinity());
    std::uint8_t arg[N + 1];
    for (int k = 2; k <= p.leaves; ++k) {
      const int lo = std::max(1, k - right.leaves), hi = std::min(k - 1, left.leaves);
      d[k] = split(k, lo, hi, arg[k]);
      // Below lo the right child's cost is flat and the sums do not fall: a tie reaches down.
      if (arg[k] == lo)
        while (arg[k] > 1 && l[arg[k] - 1] + r[k - arg[k] + 1] == d[k]) --arg[k];
    }
    if (p.leaves < N) {  // the split of a wide node made here: the first that costs d[leaves]
      // (each child at its floor; a below left.leaves is where the right child's is flat)
      arg[N] = 1;
      while (l[arg[N]] + r[N - arg[N]] != d[p.leaves]) ++arg[N];
    }
    wide_split_[m] = arg[N];
    cost[1] = area(node) + d[p.leaves];  // the least cost of a wide node of its own
    choice_[m][1] = 1;
    for (int k = 2; k <= N; ++k) {
      if (k <= p.leaves && d[k] < cost[k - 1]) {
        cost[k] = d[k], choice_[m][k] = Choice(k | arg[k] << kUsedBits);
      } else {
        cost[k] = cost[k - 1], choice_[m][k] = choice_[m][k - 1];
      }
    }
    return p;
  }

  // Appends to kids the slots binary subtree m takes when given at most k.
  void expand(std::uint32_t m, int k, std::uint32_t* kids, int& n) const {
    const BvhNode& node = bvh_.nodes[m];
    const int used = choice_[m][k] & ((1 << kUsedBits) - 1), a = choice_[m][k] >> kUsedBits;
    if (node.is_leaf() || a == 0) {
      kids[n++] = m;
      return;
    }
    expand(m + 1, a, kids, n);
    expand(node.offset, used - a, kids, n);
  }

  // The binary nodes that fill the slots of the wide node made of binary node b (inner),
  // in slot order; returns how many.
  int slots(std::uint32_t b, std::uint32_t (&kids)[N]) const {
    int n = 0;
    expand(b + 1, wide_split_[b], kids, n);
    expand(bvh_.nodes[b].offset, N - wide_split_[b], kids, n);
    return n;
  }

  // The wide nodes and leaf blocks the plan makes of binary subtree b (inner) when b is a
  // wide node; sizes[i]: those of the subtree in its slot i (inner), or 0.
  Size wide_size(std::uint32_t b, Size (&sizes)[N]) const {
    std::uint32_t kids[N];
    const int n = slots(b, kids);
    Size size{1, 0};
    for (int i = 0; i < N; ++i) sizes[i] = {};
    for (int i = 0; i < n; ++i) {
      const BvhNode& k = bvh_.nodes[kids[i]];
      if (k.is_leaf()) {
        size.blocks += blocks_of(k);
      } else {
        Size grand[N];
        sizes[i] = wide_size(kids[i], grand);
        size.nodes += sizes[i].nodes;
        size.blocks += sizes[i].blocks;
      }
    }
    return size;
  }

  static std::size_t blocks_of(const BvhNode& leaf) {
    return (leaf.count + TriangleBlock::kLanes - 1) / TriangleBlock::kLanes;
  }

  static float area(const BvhNode& k) {
    const float x = k.hi[0] - k.lo[0], y = k.hi[1] - k.lo[1], z = k.hi[2] - k.lo[2];
    return x * y + y * z + z * x;
  }

  // Writes the leaf's blocks from at.block on; returns its reference.
  std::uint32_t leaf(const BvhNode& node, Cursor& at, Tally& tally) {
    ++tally.leaves;
    const auto first = static_cast<std::uint32_t>(at.block);
    for (std::uint32_t i = 0; i < node.count; i += TriangleBlock::kLanes) {
      TriangleBlock block = TriangleBlock::empty();
      for (std::uint32_t l = 0; l < TriangleBlock::kLanes && i + l < node.count; ++l) {
        const std::uint32_t t = bvh_.order[node.offset + i + l];
        block.set(static_cast<int>(l), tris_[t], t);
      }
      if (i + TriangleBlock::kLanes >= node.count) block.prim[0] |= TriangleBlock::kLastBlock;
      blocks_[at.block++] = block;
    }
    return kLeaf | first;
  }

  // Written by the plan before they are read: their pages first touched by its tasks.
  mlib::HugePageBuffer<std::array<Choice, N + 1>> choice_;
  mlib::HugePageBuffer<std::uint8_t> wide_split_;
  const Bvh& bvh_;
  const std::span<const Triangle> tris_;
  TriangleBlocks& blocks_;
  const std::size_t first_block_;
  WideBvh<N>& out_;
};

// The tree's nodes quantized (QuantizedNode), the plain ones freed.
template <int N>
void quantize_nodes(WideBvh<N>& bvh) {
  bvh.quantized_nodes.resize(bvh.nodes.size());
  for (std::size_t k = 0; k < bvh.nodes.size(); ++k) {
    const WideNode<N>& w = bvh.nodes[k];
    QuantizedNode<N> q;
    std::memset(&q, 0, sizeof q);  // copied whole: a 4-wide node's padding is 0
    Aabb boxes[N];
    const int n = w.slots();
    for (int i = 0; i < n; ++i) boxes[i] = w.box(i);
    quantize_boxes(q, boxes, n);
    for (int i = 0; i < N; ++i) {
      q.child[i] = w.child[i];
      q.octant_order[i] = w.octant_order[i];
    }
    std::memcpy(&bvh.quantized_nodes[k], &q, sizeof q);
  }
  decltype(bvh.nodes)().swap(bvh.nodes);  // `= {}` would keep the capacity
  bvh.quantized = true;
}

}  // namespace

template <int N>
void quantize_boxes(QuantizedNode<N>& node, const Aabb* boxes, int n) {
  node.count = std::uint8_t(n);
  node.used = (std::uint32_t(1) << n) - 1;  // n <= 16
  for (int a = 0; a < 3; ++a) quantize_axis(node, boxes, n, a);
}

template <int N>
WideBvh<N> collapse_bvh(const Bvh& bvh, std::span<const Triangle> triangles,
                        TriangleBlocks& blocks, NodeLayout layout) {
  WideBvh<N> out;
  if (bvh.nodes.empty()) return out;
  const std::size_t first_block = blocks.size();
  Collapser<N> c(bvh, triangles, blocks, out);
  out.root = c.convert_root();
  out.bounds = {mlib::load_xyz(bvh.nodes[0].lo), mlib::load_xyz(bvh.nodes[0].hi)};
  if (layout == NodeLayout::quantized) quantize_nodes(out);
  out.prefetch_pushed =
      out.node_bytes() + (blocks.size() - first_block) * sizeof(TriangleBlock) >=
      kPrefetchPushedBytes;
  return out;
}

template <int N>
void refit_bvh(WideBvh<N>& bvh, std::span<const Triangle> triangles, TriangleBlocks& blocks,
               int threads) {
  if (bvh.root == kNoChild) return;
  const Aabb box = bvh.with_nodes([&](const auto* nodes) {
    using Node = std::remove_const_t<std::remove_pointer_t<decltype(nodes)>>;
    Refitter<N, Node> r(const_cast<Node*>(nodes), triangles, blocks);
    if (threads == 1 || (bvh.root & kLeaf)) return r.refit(bvh.root, 0);
    Aabb all;
    const unsigned mode = mlib::denormal_mode();
#pragma omp parallel num_threads(threads > 0 ? threads : omp_get_max_threads())
    {
      const mlib::DenormalModeScope caller_mode(mode);  // the team computes as one thread
#pragma omp single
      all = r.refit(bvh.root, 2);  // N^2 tasks: enough to balance a few threads
    }
    return all;
  });
  for (int a = 0; a < 3; ++a) {
    const float pad = box_pad(box.lo[a], box.hi[a]);
    bvh.bounds.lo[a] = box.lo[a] - pad;
    bvh.bounds.hi[a] = box.hi[a] + pad;
  }
}

template void quantize_boxes<4>(QuantizedNode<4>&, const Aabb*, int);
template void quantize_boxes<8>(QuantizedNode<8>&, const Aabb*, int);
template void quantize_boxes<16>(QuantizedNode<16>&, const Aabb*, int);

template WideBvh<4> collapse_bvh<4>(const Bvh&, std::span<const Triangle>, TriangleBlocks&,
                                    NodeLayout);
template WideBvh<8> collapse_bvh<8>(const Bvh&, std::span<const Triangle>, TriangleBlocks&,
                                    NodeLayout);
template WideBvh<16> collapse_bvh<16>(const Bvh&, std::span<const Triangle>, TriangleBlocks&,
                                      NodeLayout);

template void refit_bvh<4>(WideBvh<4>&, std::span<const Triangle>, TriangleBlocks&, int);
template void refit_bvh<8>(WideBvh<8>&, std::span<const Triangle>, TriangleBlocks&, int);
template void refit_bvh<16>(WideBvh<16>&, std::span<const Triangle>, TriangleBlocks&, int);

}  // namespace rt2
