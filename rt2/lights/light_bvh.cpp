// rt2/lights/light_bvh.cpp — building and querying the light hierarchy (see light_bvh.h).
#include "rt2/lights/light_bvh.h"

#include <omp.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>

#include "mlib/vfloat.h"
#include "rt2/lights/morton.h"
#include "rt2/lights/radix_sort.h"

namespace rt2 {
namespace {

using Clock = std::chrono::steady_clock;
using mlib::vfloat4;

double ms_since(Clock::time_point& t0) {
  const Clock::time_point now = Clock::now();
  const double ms = std::chrono::duration<double, std::milli>(now - t0).count();
  t0 = now;
  return ms;
}

// Far more than the relative rounding of any float distance (a few 2^-24).
constexpr float kRangePad = 1.0f + 0x1p-16f;

// Whether point p lies in the (padded) sphere s: centre s.xyz, radius s.w.
inline bool sphere_contains(const vec4& s, const vec4& p) {
  const float dx = p[0] - s[0], dy = p[1] - s[1], dz = p[2] - s[2];
  return dx * dx + dy * dy + dz * dz <= s[3] * s[3];
}

// Whether the (padded) sphere s meets box b: the distance from its centre to the box.
inline bool sphere_meets_box(const vec4& s, const Aabb& b) {
  float d2 = 0.0f;
  for (int a = 0; a < 3; ++a) {
    const float d = std::max(std::max(b.lo[a] - s[a], s[a] - b.hi[a]), 0.0f);
    d2 += d * d;
  }
  return d2 <= s[3] * s[3];
}

}  // namespace

LightBvh::BuildTimes LightBvh::build(const std::vector<Light>& lights, int threads) {
  return build_with(lights, [&](std::size_t i) { return lights[i].position; }, nullptr, threads);
}

LightBvh::BuildTimes LightBvh::move_and_build(std::vector<Light>& lights,
                                              const std::vector<LightPath>& paths,
                                              const LightPath::Turn& turn,
                                              const Aabb& path_bounds, int threads) {
  return build_with(
      lights,
      [&](std::size_t i) {
        const vec4 p = paths[i].at(turn);
        lights[i].position = p;
        return p;
      },
      &path_bounds, threads);
}

// position(i): light i's position (and, when the lights move, where it is moved). `known`:
// a box that holds every bounded light, or null. With it, the first pass also writes the
// Morton codes and the second is skipped when every light has a range.
template <typename Position>
LightBvh::BuildTimes LightBvh::build_with(const std::vector<Light>& lights, Position position,
                                          const Aabb* known, int threads) {
  if (threads <= 0) threads = omp_get_max_threads();
  BuildTimes times;
  Clock::time_point t0 = Clock::now();
  const std::size_t n = lights.size();
  padded_.resize(n);
  unbounded_.clear();
  if (known) {
    order_.resize(n);
    codes_.resize(n);
  }
  const MortonGrid known_grid(known ? *known : Aabb());
  // Pass 1, one chunk of [0, n) per thread: the padded spheres, the bounds of the bounded
  // lights' centres and how many each chunk has (and with known bounds, every light's code
  // as if all had a range).
  const std::size_t chunks = static_cast<std::size_t>(threads);
  const auto chunk_begin = [&](std::size_t c) { return n * c / chunks; };
  std::vector<Aabb> chunk_bounds(chunks);
  std::vector<std::size_t> bounded(chunks + 1, 0);
#pragma omp parallel for num_threads(threads) schedule(static, 1)
  for (std::size_t c = 0; c < chunks; ++c) {
    Aabb box;  // locals: the chunks' entries share cache lines
    std::size_t count = 0;
    for (std::size_t i = chunk_begin(c); i < chunk_begin(c + 1); ++i) {
      const vec4 p = position(i);
      const float range = lights[i].range;
      const bool has_range = range < kInfinity;
      padded_[i] = vec4(p[0], p[1], p[2], has_range ? range * kRangePad : kInfinity);
      if (has_range) box.grow(p);
      count += has_range;
      if (known) {
        order_[i] = static_cast<std::uint32_t>(i);
        codes_[i] = known_grid.code(p);
      }
    }
    chunk_bounds[c] = box;
    bounded[c + 1] = count;
  }
  Aabb bounds;
  for (std::size_t c = 0; c < chunks; ++c) {
    bounds.grow(chunk_bounds[c]);
    bounded[c + 1] += bounded[c];
  }
  times.lights_ms = ms_since(t0);

  // Pass 2: each chunk writes its bounded lights' indices and Morton codes from its offset.
  const std::size_t m = bounded.back();
  if (!known || m < n) {
    const MortonGrid grid(bounds);
    order_.resize(m);
    codes_.resize(m);
#pragma omp parallel for num_threads(threads) schedule(static, 1)
    for (std::size_t c = 0; c < chunks; ++c) {
      std::size_t k = bounded[c];
      for (std::size_t i = chunk_begin(c); i < chunk_begin(c + 1); ++i) {
        if (!lights[i].has_range()) continue;  // (a huge range pads to +inf: still in the tree)
        order_[k] = static_cast<std::uint32_t>(i);
        codes_[k++] = grid.code(padded_[i]);
      }
    }
  }
  if (m < n)
    for (std::size_t i = 0; i < n; ++i)
      if (!lights[i].has_range()) unbounded_.push_back(static_cast<std::uint32_t>(i));
  times.morton_ms = ms_since(t0);

  radix_sort_pairs(codes_, order_, threads, 30);
  times.sort_ms = ms_since(t0);

  // The padded spheres in Morton order (level 0's boxes and the queries' last test read
  // them in that order): a gather, prefetched ahead (its loads are random).
  sorted_.resize(m);
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::size_t k = 0; k < m; ++k) {
    if (k + 16 < m) __builtin_prefetch(&padded_[order_[k + 16]]);
    sorted_[k] = padded_[order_[k]];
  }
  // Level 0: the boxes of groups of four lights in Morton order (a walk tests a group's
  // spheres themselves); each level above boxes four of the one below, until one block
  // holds the root's children.
  const std::size_t groups = (m + 3) / 4;
  std::size_t levels = 0;
  for (std::size_t count = groups; count > 0; count = (count + 3) / 4) {
    ++levels;
    if (count <= 4) break;
  }
  levels_.resize(levels);
  std::size_t count = groups;
  for (std::size_t k = 0; k < levels; ++k) {
    std::vector<Block>& level = levels_[k];
    const std::size_t blocks = (count + 3) / 4;
    level.resize(blocks);
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::size_t b = 0; b < blocks; ++b) {
      Block& out = level[b];
      for (int j = 0; j < 4; ++j) {
        const std::size_t e = 4 * b + j;
        for (int a = 0; a < 3; ++a) {
          out.lo[a][j] = kInfinity;
          out.hi[a][j] = -kInfinity;
        }
        if (e >= count) continue;
        if (k == 0) {
          // The group's spheres' boxes, each widened by 4 ulps of |c| + r: more than the
          // rounding of c - r and c + r (half an ulp of |c| + r each) and of the widening.
          for (std::size_t l = 4 * e; l < std::min(4 * e + 4, m); ++l) {
            const vec4& s = sorted_[l];
            for (int a = 0; a < 3; ++a) {
              const float ulps = (std::fabs(s[a]) + s[3]) * 0x1p-22f;
              out.lo[a][j] = std::min(out.lo[a][j], s[a] - s[3] - ulps);
              out.hi[a][j] = std::max(out.hi[a][j], s[a] + s[3] + ulps);
            }
          }
        } else {
          const Block& in = levels_[k - 1][e];
          for (int a = 0; a < 3; ++a) {
            out.lo[a][j] = std::min(std::min(in.lo[a][0], in.lo[a][1]),
                                    std::min(in.lo[a][2], in.lo[a][3]));
            out.hi[a][j] = std::max(std::max(in.hi[a][0], in.hi[a][1]),
                                    std::max(in.hi[a][2], in.hi[a][3]));
          }
        }
      }
    }
    count = blocks;
  }
  times.tree_ms = ms_since(t0);
  return times;
}

// Depth-first over the blocks whose boxes `overlaps` (a mask of the block's four slots);
// the lights of the groups reached that `accept` are appended to `out`.
template <typename Overlaps, typename Accept>
void LightBvh::walk(Overlaps overlaps, Accept accept, std::vector<std::uint32_t>& out) const {
  out.clear();
  if (!levels_.empty()) {
    struct Entry {
      std::uint32_t level, block;
    };
    // Each step pops one entry and pushes at most four: 1 + 3 levels entries at most,
    // and 4^16 entries would hold every 32-bit index.
    Entry stack[64];
    int top = 0;
    stack[top++] = {static_cast<std::uint32_t>(levels_.size() - 1), 0};
    while (top > 0) {
      const Entry e = stack[--top];
      for (unsigned mask = overlaps(levels_[e.level][e.block]); mask != 0; mask &= mask - 1) {
        const std::uint32_t child = 4 * e.block + static_cast<std::uint32_t>(std::countr_zero(mask));
        if (e.level > 0) {
          stack[top++] = {e.level - 1, child};
        } else {  // a group of lights
          const std::size_t end = std::min<std::size_t>(4 * child + 4, sorted_.size());
          for (std::size_t l = 4 * child; l < end; ++l)
            if (accept(sorted_[l])) out.push_back(order_[l]);
        }
      }
    }
  }
  finish(out);
}

// Scene order, with the lights without a range merged in.
void LightBvh::finish(std::vector<std::uint32_t>& out) const {
  std::sort(out.begin(), out.end());
  if (unbounded_.empty()) return;
  const auto middle = static_cast<std::ptrdiff_t>(out.size());
  out.insert(out.end(), unbounded_.begin(), unbounded_.end());
  std::inplace_merge(out.begin(), out.begin() + middle, out.end());
}

void LightBvh::lights_near(const vec4& p, std::vector<std::uint32_t>& out) const {
  const vfloat4 x = vfloat4::broadcast(p[0]), y = vfloat4::broadcast(p[1]),
                z = vfloat4::broadcast(p[2]);
  walk(
      [&](const Block& b) {
        return bits((vfloat4::load(b.lo[0]) <= x) & (x <= vfloat4::load(b.hi[0])) &
                    (vfloat4::load(b.lo[1]) <= y) & (y <= vfloat4::load(b.hi[1])) &
                    (vfloat4::load(b.lo[2]) <= z) & (z <= vfloat4::load(b.hi[2])));
      },
      [&](const vec4& s) { return sphere_contains(s, p); }, out);
}

void LightBvh::lights_near(const Aabb& box, std::vector<std::uint32_t>& out) const {
  const vfloat4 lx = vfloat4::broadcast(box.lo[0]), ly = vfloat4::broadcast(box.lo[1]),
                lz = vfloat4::broadcast(box.lo[2]), hx = vfloat4::broadcast(box.hi[0]),
                hy = vfloat4::broadcast(box.hi[1]), hz = vfloat4::broadcast(box.hi[2]);
  walk(
      [&](const Block& b) {
        return bits((vfloat4::load(b.lo[0]) <= hx) & (lx <= vfloat4::load(b.hi[0])) &
                    (vfloat4::load(b.lo[1]) <= hy) & (ly <= vfloat4::load(b.hi[1])) &
                    (vfloat4::load(b.lo[2]) <= hz) & (lz <= vfloat4::load(b.hi[2])));
      },
      [&](const vec4& s) { return sphere_meets_box(s, box); }, out);
}

void LightBvh::lights_near_brute_force(const Aabb& box, std::vector<std::uint32_t>& out) const {
  out.clear();
  for (std::size_t i = 0; i < padded_.size(); ++i)
    if (sphere_meets_box(padded_[i], box)) out.push_back(static_cast<std::uint32_t>(i));
}

std::size_t LightBvh::bytes() const {
  std::size_t b = (padded_.capacity() + sorted_.capacity()) * sizeof(vec4) +
                  (unbounded_.capacity() + order_.capacity() + codes_.capacity()) *
                      sizeof(std::uint32_t);
  for (const auto& level : levels_) b += level.capacity() * sizeof(Block);
  return b;
}

}  // namespace rt2
