// rt2/bvh/linear_build.cpp — the linear BVH (see linear_build.h).
#include "rt2/bvh/linear_build.h"

#include <omp.h>

#include <algorithm>
#include <bit>
#include <cstdint>

#include "mlib/fpmode.h"
#include "rt2/lights/morton.h"
#include "rt2/lights/radix_sort.h"

namespace rt2 {

namespace {

// Subtrees of fewer primitives are built by the task that reaches them.
constexpr std::uint32_t kTaskGrain = 4096;

struct LinearBuilder {
  const std::vector<Aabb>& boxes;
  const std::vector<std::uint32_t>& codes;  // sorted
  Bvh& bvh;

  // Where [lo, hi) splits: after the last code that shares the run's highest differing bit
  // with codes[lo] (the middle when all codes are equal).
  std::uint32_t split(std::uint32_t lo, std::uint32_t hi) const {
    const std::uint32_t first = codes[lo], last = codes[hi - 1];
    if (first == last) return lo + (hi - lo) / 2;
    const int common = std::countl_zero(first ^ last);
    std::uint32_t a = lo, b = hi - 1;  // codes[a] has the bit clear, codes[b] set
    while (b - a > 1) {
      const std::uint32_t m = a + (b - a) / 2;
      (std::countl_zero(first ^ codes[m]) > common ? a : b) = m;
    }
    return b;
  }

  // Node `at` over primitives [lo, hi) (in code order), its subtree in the 2 (hi - lo) - 1
  // nodes from `at`; returns its box.
  Aabb build(std::uint32_t at, std::uint32_t lo, std::uint32_t hi) {
    BvhNode& n = bvh.nodes[at];
    Aabb box;
    if (hi - lo == 1) {
      box = boxes[bvh.order[lo]];
      n.offset = lo;
      n.count = 1;
    } else {
      const std::uint32_t s = split(lo, hi);
      const std::uint32_t second = at + 2 * (s - lo);
      Aabb a, b;
      if (hi - lo >= kTaskGrain) {
#pragma omp task shared(a)
        a = build(at + 1, lo, s);
        b = build(second, s, hi);
#pragma omp taskwait
      } else {
        a = build(at + 1, lo, s);
        b = build(second, s, hi);
      }
      box = a;
      box.grow(b);
      n.offset = second;
      n.count = 0;
    }
    for (int k = 0; k < 3; ++k) {
      n.lo[k] = box.lo[k];
      n.hi[k] = box.hi[k];
    }
    return box;
  }
};

}  // namespace

void build_linear_bvh(const std::vector<Aabb>& boxes, int threads, Bvh& bvh) {
  const auto n = static_cast<std::uint32_t>(boxes.size());
  bvh.stats = {};
  if (n == 0) {
    bvh.nodes.clear();
    bvh.order.clear();
    return;
  }
  const int team = threads > 0 ? threads : omp_get_max_threads();
  Aabb centres;
  for (const Aabb& b : boxes) centres.grow(b.center());
  const MortonGrid grid(centres);
  // Scratch kept between frames (named through a reference: inside the parallel loop the
  // thread_local's name would be each thread's own).
  thread_local std::vector<std::uint32_t> scratch;
  std::vector<std::uint32_t>& codes = scratch;
  codes.resize(n);
  bvh.order.resize(n);
  const unsigned mode = mlib::denormal_mode();
#pragma omp parallel num_threads(team) if (n >= 16384)
  {
    const mlib::DenormalModeScope caller_mode(mode);  // the team computes as one thread
#pragma omp for schedule(static)
    for (std::uint32_t i = 0; i < n; ++i) {
      codes[i] = grid.code(boxes[i].center());
      bvh.order[i] = i;
    }
  }
  radix_sort_pairs(codes, bvh.order, team, 30);
  bvh.nodes.resize(2 * std::size_t(n) - 1);
  LinearBuilder builder{boxes, codes, bvh};
#pragma omp parallel num_threads(team) if (n >= kTaskGrain)
  {
    const mlib::DenormalModeScope caller_mode(mode);
#pragma omp single
    builder.build(0, 0, n);
  }
  bvh.stats.nodes = 2 * n - 1;
  bvh.stats.leaves = n;
  bvh.stats.max_leaf_prims = 1;
}

}  // namespace rt2
