// rt2/bvh/build.cpp — top-down BVH construction: midpoint or binned SAH splits.
#include "rt2/bvh/build.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "rt2/error.h"

namespace rt2 {
namespace {

constexpr std::uint32_t kMedianBelowDepth = 64;

class Builder {
 public:
  Builder(const std::vector<Aabb>& boxes, const BvhConfig& config, Bvh& out)
      : boxes_(boxes), config_(config), out_(out) {
    centroids_.reserve(boxes.size());
    for (const Aabb& b : boxes) centroids_.push_back(b.center());
    out_.order.resize(boxes.size());
    for (std::uint32_t i = 0; i < boxes.size(); ++i) out_.order[i] = i;
    out_.nodes.reserve(2 * boxes.size());
  }

  std::uint32_t build(std::uint32_t begin, std::uint32_t end, std::uint32_t depth) {
    const auto index = static_cast<std::uint32_t>(out_.nodes.size());
    out_.nodes.emplace_back();
    Aabb bounds, cbounds;
    for (std::uint32_t i = begin; i < end; ++i) {
      bounds.grow(boxes_[out_.order[i]]);
      cbounds.grow(centroids_[out_.order[i]]);
    }
    BvhNode& node = out_.nodes[index];
    for (int a = 0; a < 3; ++a) {
      // Padded by 4 ulps of the coordinates: the triangle test rounds too, and may accept a
      // ray that passes a fraction of an ulp outside a triangle (a grazing ray along a box
      // edge); the box around it must not reject what the test inside would accept.
      const float pad = std::max(std::fabs(bounds.lo[a]), std::fabs(bounds.hi[a])) * 0x1p-21f +
                        std::numeric_limits<float>::min();
      node.lo[a] = bounds.lo[a] - pad;
      node.hi[a] = bounds.hi[a] + pad;
    }
    BvhStats& st = out_.stats;
    st.max_depth = std::max(st.max_depth, depth);
    const std::uint32_t count = end - begin;
    if (count <= config_.max_leaf_size) {
      node.offset = begin;
      node.count = count;
      ++st.leaves;
      st.max_leaf_prims = std::max(st.max_leaf_prims, count);
      return index;
    }
    const std::uint32_t mid = split(begin, end, cbounds, depth);
    build(begin, mid, depth + 1);
    const std::uint32_t right = build(mid, end, depth + 1);
    out_.nodes[index].offset = right;  // `node` may dangle: the vector grew
    out_.nodes[index].count = 0;
    return index;
  }

 private:
  float centroid(std::uint32_t prim, int axis) const { return centroids_[prim][axis]; }

  // Partitions [begin, end) and returns the first index of the right side, never begin
  // or end.
  std::uint32_t split(std::uint32_t begin, std::uint32_t end, const Aabb& cbounds,
                      std::uint32_t depth) {
    const int axis = cbounds.longest_axis();
    const bool flat = !(cbounds.extent()[axis] > 0.0f);
    if (flat || depth >= kMedianBelowDepth) return median(begin, end, axis);
    const std::uint32_t mid = config_.split == Split::sah ? sah(begin, end, cbounds)
                                                          : midpoint(begin, end, cbounds, axis);
    return mid == begin || mid == end ? median(begin, end, axis) : mid;
  }

  std::uint32_t median(std::uint32_t begin, std::uint32_t end, int axis) {
    const std::uint32_t mid = begin + (end - begin) / 2;
    auto* o = out_.order.data();
    std::nth_element(o + begin, o + mid, o + end, [&](std::uint32_t a, std::uint32_t b) {
      return centroid(a, axis) < centroid(b, axis);
    });
    return mid;
  }

  // The thesis: cut the box in the middle of its longest axis.
  std::uint32_t midpoint(std::uint32_t begin, std::uint32_t end, const Aabb& cbounds, int axis) {
    const float cut = cbounds.center()[axis];
    auto* o = out_.order.data();
    auto* m = std::partition(o + begin, o + end,
                             [&](std::uint32_t p) { return centroid(p, axis) < cut; });
    return static_cast<std::uint32_t>(m - o);
  }

  // Binned SAH (Wald 2007): for each axis, centroids go into bins; the plane between two
  // bins minimising A_left * N_left + A_right * N_right wins.
  std::uint32_t sah(std::uint32_t begin, std::uint32_t end, const Aabb& cbounds) {
    const int bins = config_.sah_bins;
    struct Bin {
      Aabb box;
      std::uint32_t count = 0;
    };
    std::vector<Bin> bin(bins);
    std::vector<float> right_area(bins);
    std::vector<std::uint32_t> right_count(bins);
    float best_cost = kInfinity;
    int best_axis = -1, best_plane = 0;
    for (int axis = 0; axis < 3; ++axis) {
      const float lo = cbounds.lo[axis], extent = cbounds.extent()[axis];
      if (!(extent > 0.0f)) continue;
      const float scale = float(bins) / extent;
      std::fill(bin.begin(), bin.end(), Bin{});
      for (std::uint32_t i = begin; i < end; ++i) {
        const std::uint32_t p = out_.order[i];
        Bin& b = bin[bin_of(centroid(p, axis), lo, scale, bins)];
        b.box.grow(boxes_[p]);
        ++b.count;
      }
      Aabb acc;
      std::uint32_t n = 0;
      for (int k = bins - 1; k > 0; --k) {  // right side of plane k-1 | k
        acc.grow(bin[k].box);
        n += bin[k].count;
        right_area[k] = acc.area();
        right_count[k] = n;
      }
      acc = Aabb();
      n = 0;
      for (int k = 0; k < bins - 1; ++k) {  // plane between bin k and bin k+1
        acc.grow(bin[k].box);
        n += bin[k].count;
        if (n == 0 || right_count[k + 1] == 0) continue;
        const float cost = acc.area() * float(n) + right_area[k + 1] * float(right_count[k + 1]);
        if (cost < best_cost) {
          best_cost = cost;
          best_axis = axis;
          best_plane = k;
        }
      }
    }
    if (best_axis < 0) return begin;  // no plane separates anything: median fallback
    const float lo = cbounds.lo[best_axis];
    const float scale = float(bins) / cbounds.extent()[best_axis];
    auto* o = out_.order.data();
    auto* m = std::partition(o + begin, o + end, [&](std::uint32_t p) {
      return bin_of(centroid(p, best_axis), lo, scale, bins) <= best_plane;
    });
    return static_cast<std::uint32_t>(m - o);
  }

  static int bin_of(float c, float lo, float scale, int bins) {
    const int k = static_cast<int>((c - lo) * scale);
    return std::clamp(k, 0, bins - 1);
  }

  const std::vector<Aabb>& boxes_;
  const BvhConfig& config_;
  Bvh& out_;
  std::vector<vec4> centroids_;
};

}  // namespace

Bvh build_bvh(const std::vector<Aabb>& boxes, const BvhConfig& config) {
  if (config.max_leaf_size == 0) throw Error("BVH max leaf size must be >= 1");
  if (config.sah_bins < 2 || config.sah_bins > 1024)
    throw Error("BVH SAH bins must be in [2, 1024]");
  const auto t0 = std::chrono::steady_clock::now();
  Bvh bvh;
  if (!boxes.empty()) {
    Builder builder(boxes, config, bvh);
    builder.build(0, static_cast<std::uint32_t>(boxes.size()), 0);
  }
  bvh.stats.nodes = static_cast<std::uint32_t>(bvh.nodes.size());
  bvh.stats.build_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return bvh;
}

}  // namespace rt2
