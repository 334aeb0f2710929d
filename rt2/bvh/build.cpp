// rt2/bvh/build.cpp — top-down BVH construction: midpoint or binned SAH splits.
//
// The primitives travel as 32-byte records (box and index) that each split partitions in
// place, so every pass over a node's primitives reads memory in order. A node's bounds
// come from its parent's bins and its centroid bounds from a pass after the partition (after
// a median split, one pass gives both), and one pass bins all three axes at once.
#include "rt2/bvh/build.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>

#include <omp.h>

#include "mlib/fpmode.h"
#include "mlib/huge_pages.h"
#include "rt2/base/error.h"

namespace rt2 {
namespace {

constexpr std::uint32_t kMedianBelowDepth = 64;

// A primitive's box and its index, 32 bytes.
struct PrimBox {
  float lo[3];
  std::uint32_t index;
  float hi[3];
  std::uint32_t pad;
  vec4 lo4() const { return mlib::load_xyz(lo); }
  vec4 hi4() const { return mlib::load_xyz(hi); }
  vec4 centroid2() const { return lo4() + hi4(); }  // twice the centroid
};
static_assert(sizeof(PrimBox) == 32);

struct Bin {
  Aabb box;  // the primitives' boxes
  std::uint32_t count = 0;
};

// On a team of several threads, the two sides of a split of at least this many primitives,
// down to this depth, are built at once (below, the copy costs more than the second thread
// saves): the left one in place, the right one by an OpenMP task into nodes of its own,
// appended after, in the order a serial build makes them: the tree is the same node for
// node at any thread count.
constexpr std::uint32_t kTaskPrims = 1u << 18;
constexpr std::uint32_t kTaskDepth = 4;
// A split whose passes are shared (Builder::shared_pass) bins in this many tasks, whatever
// the team's size.
constexpr std::uint32_t kChunks = 8;

using Nodes = decltype(Bvh::nodes);

// Builds subtrees over the shared primitive records into `nodes` (indices from 0, primitive
// offsets absolute) and `stats`.
class Builder {
 public:
  Builder(const BvhConfig& config, PrimBox* prims, Nodes& nodes, BvhStats& stats)
      : config_(config), prims_(prims), nodes_(nodes), stats_(stats),
        bins_(2 * 3 * std::size_t(config.sah_bins)), right_(std::size_t(config.sah_bins)) {}

  // Bounds and (doubled) centroid bounds of prims_[begin, end).
  void measure(std::uint32_t begin, std::uint32_t end, Aabb& bounds, Aabb& cbounds) const {
    bounds = cbounds = Aabb();
    for (std::uint32_t i = begin; i < end; ++i) {
      const vec4 lo = prims_[i].lo4(), hi = prims_[i].hi4();
      bounds.lo = mlib::min(bounds.lo, lo);
      bounds.hi = mlib::max(bounds.hi, hi);
      cbounds.grow(lo + hi);
    }
  }

  // The subtree over prims_[begin, end), depth first from nodes_'s end; returns its root.
  std::uint32_t build(std::uint32_t begin, std::uint32_t end, const Aabb& bounds,
                      const Aabb& cbounds, std::uint32_t depth) {
    const auto index = static_cast<std::uint32_t>(nodes_.size());
    nodes_.emplace_back();
    BvhNode& node = nodes_[index];
    for (int a = 0; a < 3; ++a) {
      const float pad = box_pad(bounds.lo[a], bounds.hi[a]);
      node.lo[a] = bounds.lo[a] - pad;
      node.hi[a] = bounds.hi[a] + pad;
    }
    stats_.max_depth = std::max(stats_.max_depth, depth);
    const std::uint32_t count = end - begin;
    if (count <= config_.max_leaf_size) {
      node.offset = begin;
      node.count = count;
      ++stats_.leaves;
      stats_.max_leaf_prims = std::max(stats_.max_leaf_prims, count);
      return index;
    }
    Aabb lb, lcb, rb, rcb;
    const std::uint32_t mid = split(begin, end, cbounds, depth, lb, lcb, rb, rcb);
    std::uint32_t right;
    if (depth < kTaskDepth && in_parallel(count)) {
      right = build_sides_as_tasks(begin, mid, end, lb, lcb, rb, rcb, depth + 1);
    } else {
      build(begin, mid, lb, lcb, depth + 1);
      right = build(mid, end, rb, rcb, depth + 1);
    }
    nodes_[index].offset = right;  // `node` may dangle: the vector grew
    nodes_[index].count = 0;
    return index;
  }

 private:
  // Both sides of a split at once: the left one here, into nodes_ after its parent as
  // build would place it, the right one by a task into nodes of its own, appended after
  // with its inner nodes' offsets moved; returns the right side's root.
  std::uint32_t build_sides_as_tasks(std::uint32_t begin, std::uint32_t mid, std::uint32_t end,
                                     const Aabb& lb, const Aabb& lcb, const Aabb& rb,
                                     const Aabb& rcb, std::uint32_t depth) {
    Nodes right_nodes;
    BvhStats right_stats;
    // An exception (out of memory) may not leave a task: each side keeps its own, and the
    // left one's is thrown after the task has ended, as the serial build would throw it.
    std::exception_ptr errors[2];
#pragma omp task default(shared)
    try {
      right_nodes.reserve(2 * std::size_t(end - mid));
      Builder(config_, prims_, right_nodes, right_stats).build(mid, end, rb, rcb, depth);
    } catch (...) {
      errors[1] = std::current_exception();
    }
    try {
      build(begin, mid, lb, lcb, depth);
    } catch (...) {
      errors[0] = std::current_exception();
    }
#pragma omp taskwait
    for (const std::exception_ptr& e : errors)
      if (e) std::rethrow_exception(e);
    const auto root = static_cast<std::uint32_t>(nodes_.size());
    for (BvhNode n : right_nodes) {
      if (n.count == 0) n.offset += root;  // an inner node names its second child
      nodes_.push_back(n);
    }
    stats_.leaves += right_stats.leaves;
    stats_.max_depth = std::max(stats_.max_depth, right_stats.max_depth);
    stats_.max_leaf_prims = std::max(stats_.max_leaf_prims, right_stats.max_leaf_prims);
    return root;
  }

  // Partitions [begin, end) and returns the first index of the right side, never begin or
  // end, with the bounds and centroid bounds of both sides.
  std::uint32_t split(std::uint32_t begin, std::uint32_t end, const Aabb& cbounds,
                      std::uint32_t depth, Aabb& lb, Aabb& lcb, Aabb& rb, Aabb& rcb) {
    const int axis = cbounds.longest_axis();
    const bool flat = !(cbounds.extent()[axis] > 0.0f);
    std::uint32_t mid = begin;
    if (!flat && depth < kMedianBelowDepth) {
      mid = config_.split == Split::sah ? sah(begin, end, depth, cbounds, lb, lcb, rb, rcb)
                                        : midpoint(begin, end, cbounds, axis);
      if (mid != begin && mid != end && config_.split == Split::sah) return mid;
    }
    if (mid == begin || mid == end) mid = median(begin, end, axis);
    measure(begin, mid, lb, lcb);
    measure(mid, end, rb, rcb);
    return mid;
  }

  std::uint32_t median(std::uint32_t begin, std::uint32_t end, int axis) {
    const std::uint32_t mid = begin + (end - begin) / 2;
    PrimBox* p = prims_;
    std::nth_element(p + begin, p + mid, p + end, [axis](const PrimBox& a, const PrimBox& b) {
      return a.lo[axis] + a.hi[axis] < b.lo[axis] + b.hi[axis];
    });
    return mid;
  }

  // The thesis: cut the box in the middle of its longest axis.
  std::uint32_t midpoint(std::uint32_t begin, std::uint32_t end, const Aabb& cbounds, int axis) {
    const float cut = cbounds.center()[axis];
    return partition(begin, end, [&](const PrimBox& b) { return b.lo[axis] + b.hi[axis] < cut; });
  }

  // Binned SAH (Wald 2007): centroids go into bins along each axis (all three in one pass);
  // the plane between two bins minimising A_left * cost(N_left) + A_right * cost(N_right)
  // wins, where cost(n) counts blocks of config.sah_block primitives (Embree's rule: a leaf
  // is tested a block at a time, so 4 triangles cost as much as 1). Returns begin when no
  // plane separates anything.
  std::uint32_t sah(std::uint32_t begin, std::uint32_t end, std::uint32_t depth,
                    const Aabb& cbounds, Aabb& lb, Aabb& lcb, Aabb& rb, Aabb& rcb) {
    // Bins in proportion to the primitives, 4 + n / 20 up to sah_bins (Embree's mapping):
    // most nodes are small, and planes between nearly empty bins find little.
    const int bins = std::min(config_.sah_bins, 4 + int((end - begin) / 20));
    const int log_block = std::countr_zero(config_.sah_block);  // a power of two
    const std::uint32_t round = config_.sah_block - 1;
    const vec4 lo = cbounds.lo, extent = cbounds.extent();
    float scale[3];
    for (int a = 0; a < 3; ++a) scale[a] = extent[a] > 0.0f ? float(bins) / extent[a] : 0.0f;
    // Two sets of bins, even primitives into one and odd into the other, merged after:
    // neighbours in the array are neighbours in space and mostly fall into the same bin, so
    // with one set each update would wait for the previous one to reach memory.
    Bin* bx = bins_.data();
    Bin* by = bx + 3 * bins;
    std::fill(bx, by + 3 * bins, Bin{});
    const vec4 scale4{scale[0], scale[1], scale[2], 0.0f};
    // A primitive's bin on each axis (its doubled centroid's), k[0 .. 2]: the binning and
    // the partition below both take it from here, so they cannot disagree.
    const auto bins_of = [&](const PrimBox& p, std::int32_t (&k)[4]) {
      mlib::truncate_clamp((p.centroid2() - lo) * scale4, 0, bins - 1, k);
    };
    const auto add = [&](Bin* set, const PrimBox& p) {
      const vec4 plo = p.lo4(), phi = p.hi4();
      std::int32_t k[4];
      bins_of(p, k);
      for (int a = 0; a < 3; ++a) {
        Bin& b = set[a * bins + k[a]];
        b.box.lo = mlib::min(b.box.lo, plo);
        b.box.hi = mlib::max(b.box.hi, phi);
        ++b.count;
      }
    };
    const auto bin_range = [&](Bin* even, Bin* odd, std::uint32_t first, std::uint32_t last) {
      std::uint32_t i = first;
      for (; i + 1 < last; i += 2) {
        add(even, prims_[i]);
        add(odd, prims_[i + 1]);
      }
      if (i < last) add(even, prims_[i]);
    };
    const int sets = 3 * bins;  // bins per set
    if (shared_pass(end - begin, depth)) {
      // Chunks binned by tasks into sets of their own, merged after: the bins are the same
      // in any grouping (box bounds and counts).
      std::vector<Bin> chunk_bins(std::size_t(2 * sets) * kChunks);
      const std::uint32_t step = (end - begin + kChunks - 1) / kChunks;
#pragma omp taskloop default(shared) grainsize(1)
      for (std::uint32_t c = 0; c < kChunks; ++c) {
        Bin* even = chunk_bins.data() + std::size_t(2 * sets) * c;
        bin_range(even, even + sets, begin + std::min(end - begin, c * step),
                  begin + std::min(end - begin, (c + 1) * step));
      }
      for (std::uint32_t c = 0; c < 2 * kChunks; ++c)
        merge_bins(bx, chunk_bins.data() + std::size_t(sets) * c, sets);
    } else {
      bin_range(bx, by, begin, end);
      merge_bins(bx, by, sets);
    }
    float best_cost = kInfinity;
    int best_axis = -1, best_plane = 0;
    for (int axis = 0; axis < 3; ++axis) {
      if (!(extent[axis] > 0.0f)) continue;
      const Bin* b = bx + axis * bins;
      Aabb acc;
      std::uint32_t n = 0;
      for (int k = bins - 1; k > 0; --k) {  // right side of plane k-1 | k
        acc.grow(b[k].box);
        n += b[k].count;
        right_[k] = {acc.area(), n};
      }
      acc = Aabb();
      n = 0;
      for (int k = 0; k < bins - 1; ++k) {  // plane between bin k and bin k+1
        acc.grow(b[k].box);
        n += b[k].count;
        const std::uint32_t rn = right_[k + 1].count;
        if (n == 0 || rn == 0) continue;
        const float cost = acc.area() * float((n + round) >> log_block) +
                           right_[k + 1].area * float((rn + round) >> log_block);
        if (cost < best_cost) {
          best_cost = cost;
          best_axis = axis;
          best_plane = k;
        }
      }
    }
    if (best_axis < 0) return begin;
    lb = rb = Aabb();
    const Bin* b = bx + best_axis * bins;
    for (int k = 0; k < bins; ++k) (k <= best_plane ? lb : rb).grow(b[k].box);
    const std::uint32_t mid = partition(begin, end, [&](const PrimBox& q) {
      std::int32_t k[4];
      bins_of(q, k);
      return k[best_axis] <= best_plane;
    });
    // The sides' centroid bounds in a pass of their own: cheaper than a centroid box per
    // bin, updated three times per primitive during binning.
    if (shared_pass(end - begin, depth)) {
#pragma omp task default(shared)
      lcb = centroid_bounds(begin, mid);
      rcb = centroid_bounds(mid, end);
#pragma omp taskwait
    } else {
      lcb = centroid_bounds(begin, mid);
      rcb = centroid_bounds(mid, end);
    }
    return mid;
  }

  // Whether the sides of a split of `count` primitives may be built at once.
  static bool in_parallel(std::uint32_t count) {
    return count >= kTaskPrims && omp_get_num_threads() > 1;
  }

  // Whether a pass over the `count` primitives of a node at `depth` is split between tasks:
  // while the subtrees built at once are fewer than the threads. Deeper, every thread
  // builds a subtree of its own, and a thread waiting for the pass's tasks could take up
  // a whole subtree's task in the meantime and hold up the node it is splitting.
  static bool shared_pass(std::uint32_t count, std::uint32_t depth) {
    return in_parallel(count) && depth < 31 && (1 << depth) < omp_get_num_threads();
  }

  // The bins of `from` added to those of `to`, `count` of each.
  static void merge_bins(Bin* to, const Bin* from, int count) {
    for (int k = 0; k < count; ++k) {
      to[k].box.grow(from[k].box);
      to[k].count += from[k].count;
    }
  }

  // The (doubled) centroid bounds of prims_[begin, end), two primitives at a time.
  Aabb centroid_bounds(std::uint32_t begin, std::uint32_t end) const {
    Aabb even, odd;
    std::uint32_t i = begin;
    for (; i + 1 < end; i += 2) {
      even.grow(prims_[i].centroid2());
      odd.grow(prims_[i + 1].centroid2());
    }
    if (i < end) even.grow(prims_[i].centroid2());
    even.grow(odd);
    return even;
  }

  // Moves the primitives for which left(p) holds to the front of [begin, end) and returns
  // where the others start. Without a branch on left(p) (Lomuto's scheme, swapping every
  // element, with the left run's end advanced by the predicate): which side a primitive
  // falls on cannot be predicted, and std::partition's mispredicted branches cost more than
  // the extra copies.
  template <class Left>
  std::uint32_t partition(std::uint32_t begin, std::uint32_t end, Left left) {
    PrimBox* p = prims_;
    std::uint32_t j = begin;
    for (std::uint32_t i = begin; i < end; ++i) {
      const PrimBox q = p[i];
      const bool l = left(q);
      p[i] = p[j];  // [j, i) holds right ones: p[j] is one, or j == i
      p[j] = q;
      j += l ? 1u : 0u;
    }
    return j;
  }

  struct Side {
    float area;
    std::uint32_t count;
  };

  const BvhConfig& config_;
  PrimBox* prims_;  // shared by the tasks, each partitioning its own range
  Nodes& nodes_;
  BvhStats& stats_;
  std::vector<Bin> bins_;    // [set][axis][bin], two sets (see sah)
  std::vector<Side> right_;  // [bin]: what lies right of the plane before it
};

}  // namespace

Bvh build_bvh(std::uint32_t count, const std::function<Aabb(std::uint32_t)>& box_of,
              const BvhConfig& config) {
  if (config.max_leaf_size == 0) throw Error("BVH max leaf size must be >= 1");
  if (config.sah_bins < 2 || config.sah_bins > 1024)
    throw Error("BVH SAH bins must be in [2, 1024]");
  if (config.sah_block < 1 || config.sah_block > 64 || !std::has_single_bit(config.sah_block))
    throw Error("BVH SAH block size must be a power of two in [1, 64]");
  const auto t0 = std::chrono::steady_clock::now();
  Bvh bvh;
  if (count > 0) {
    // partitioned over and over: huge pages once large
    mlib::HugePageBuffer<PrimBox> prims(count);  // each thread writes its part first
    // A full binary tree over n primitives has at most 2n - 1 nodes.
    bvh.nodes.reserve(2 * std::size_t(count));
    Builder root(config, prims.data(), bvh.nodes, bvh.stats);
    Aabb bounds, cbounds;
    std::exception_ptr error;  // thrown after the parallel region, which it may not leave
    const unsigned mode = mlib::denormal_mode();
#pragma omp parallel if (count >= kTaskPrims)
    {
      const mlib::DenormalModeScope caller_mode(mode);  // the team computes as one thread
      Aabb b, cb;
#pragma omp for schedule(static) nowait
      for (std::uint32_t i = 0; i < count; ++i) {
        const Aabb box = box_of(i);
        for (int a = 0; a < 3; ++a) {
          prims[i].lo[a] = box.lo[a];
          prims[i].hi[a] = box.hi[a];
        }
        prims[i].index = i;
        prims[i].pad = 0;
        b.grow(box);
        cb.grow(box.lo + box.hi);
      }
#pragma omp critical
      {
        bounds.grow(b);  // min and max: the same in any order
        cbounds.grow(cb);
      }
#pragma omp barrier
#pragma omp single
      try {
        root.build(0, count, bounds, cbounds, 0);
      } catch (...) {
        error = std::current_exception();
      }
    }
    if (error) std::rethrow_exception(error);
    bvh.order.resize(count);
    for (std::uint32_t i = 0; i < count; ++i) bvh.order[i] = prims[i].index;
  }
  bvh.stats.nodes = static_cast<std::uint32_t>(bvh.nodes.size());
  bvh.stats.build_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return bvh;
}

Bvh build_bvh(const std::vector<Aabb>& boxes, const BvhConfig& config) {
  return build_bvh(
      static_cast<std::uint32_t>(boxes.size()), [&boxes](std::uint32_t i) { return boxes[i]; },
      config);
}

}  // namespace rt2
