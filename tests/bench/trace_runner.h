// tests/bench/trace_runner.h — what bench_trace runs: a set of rays, one engine's way of
// tracing it in parallel chunks, and its answers.
//
// A Runner is an engine's body over work units [begin, end) (rays, or 16-ray tiles for
// packets) that writes the engine's answers for those units; run_chunks calls it from a
// oneTBB task_arena of a given thread count. rt2's runner talks to rt2 only through the
// batch queries of rt2/render/trace.h.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "mlib/fpmode.h"
#include "rt2/render/trace.h"

namespace bench {

using rt2::Hit;
using rt2::Ray;

// Rays with their interval ends (0, t_max[i]), traced by every engine in this order.
struct RaySet {
  std::string name;
  bool occlusion = false;  // shadow: any hit; the others: closest hit
  std::vector<Ray> rays;
  std::vector<float> t_max;
  // Coherent sets only (else empty): the rays of 4 x 4 tile k are [tile_begin[k],
  // tile_begin[k + 1]), ray i in packet lane lane[i] (its pixel in the tile, row-major).
  std::vector<std::uint32_t> tile_begin;
  std::vector<std::uint8_t> lane;
  std::size_t size() const { return rays.size(); }
  std::size_t tiles() const { return tile_begin.empty() ? 0 : tile_begin.size() - 1; }
};

// body(begin, end) over [0, units) in chunks of `chunk` units on `arena`'s threads, FTZ and
// DAZ set in each; returns the wall time in seconds.
inline double run_chunks(tbb::task_arena& arena, std::size_t units, std::size_t chunk,
                         const std::function<void(std::size_t, std::size_t)>& body) {
  const std::size_t chunks = (units + chunk - 1) / chunk;
  const auto t0 = std::chrono::steady_clock::now();
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, chunks, 1),
        [&](const tbb::blocked_range<std::size_t>& r) {
          mlib::set_flush_denormals();
          for (std::size_t c = r.begin(); c != r.end(); ++c)
            body(c * chunk, std::min(units, (c + 1) * chunk));
        },
        tbb::simple_partitioner());
  });
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// An engine's answers for one set: hits (closest) or occluded flags (shadow).
struct Answers {
  std::vector<Hit> hits;
  std::vector<std::uint8_t> occluded;
  bool hit(std::size_t i) const { return hits.empty() ? occluded[i] != 0 : hits[i].found(); }
  std::size_t count() const {
    std::size_t n = 0;
    for (std::size_t i = 0; i < std::max(hits.size(), occluded.size()); ++i) n += hit(i);
    return n;
  }
};

// One way of tracing a set: `units` work units (rays, or tiles for packets) and a body.
struct Runner {
  std::string engine;
  std::size_t units = 0;
  std::size_t chunk = 0;
  std::function<void(std::size_t, std::size_t)> body;
  // The closest hit of ray i in (0, t_max[i]) by this engine, for explaining a
  // disagreement about occlusion.
  std::function<Hit(std::size_t)> closest_one;
  Answers answers;
  std::vector<double> mrays;

  // Move-only: `body` writes into `answers`' arrays, which a move keeps and a copy would not.
  Runner() = default;
  Runner(Runner&&) noexcept = default;
  Runner& operator=(Runner&&) noexcept = default;
  Runner(const Runner&) = delete;
  Runner& operator=(const Runner&) = delete;
};

// rt2: trace_closest / trace_occluded over each chunk.
inline Runner rt2_runner(const rt2::Accel& acc, const rt2::TraceOptions& opt,
                         const RaySet& set, std::size_t chunk) {
  Runner r;
  r.engine = "rt2";
  r.units = set.size();
  r.chunk = chunk;
  if (set.occlusion) {
    r.answers.occluded.resize(set.size());
    r.body = [&acc, opt, &set, out = r.answers.occluded.data()](std::size_t b, std::size_t e) {
      rt2::trace_occluded(acc, opt, set.rays.data() + b, set.t_max.data() + b, e - b, out + b);
    };
  } else {
    r.answers.hits.resize(set.size());
    r.body = [&acc, opt, &set, out = r.answers.hits.data()](std::size_t b, std::size_t e) {
      rt2::trace_closest(acc, opt, set.rays.data() + b, set.t_max.data() + b, e - b, out + b);
    };
  }
  r.closest_one = [&acc, opt, &set](std::size_t i) {
    Hit h;
    rt2::trace_closest(acc, opt, &set.rays[i], &set.t_max[i], 1, &h);
    return h;
  };
  return r;
}

// rt2's packets: trace_closest_packets / trace_occluded_packets over each chunk of 4 x 4
// tiles (coherent sets only), a tile's rays in one packet.
inline Runner rt2_packet_runner(const rt2::Accel& acc, const rt2::TraceOptions& opt,
                                const RaySet& set, std::size_t chunk) {
  Runner r = rt2_runner(acc, opt, set, chunk);
  r.engine = "rt2_packets";
  r.units = set.tiles();
  r.chunk = std::max<std::size_t>(1, chunk / 16);
  if (set.occlusion) {
    r.body = [&acc, opt, &set, out = r.answers.occluded.data()](std::size_t b, std::size_t e) {
      rt2::trace_occluded_packets(acc, opt, set.rays.data(), set.t_max.data(),
                                  set.tile_begin.data() + b, e - b, out);
    };
  } else {
    r.body = [&acc, opt, &set, out = r.answers.hits.data()](std::size_t b, std::size_t e) {
      rt2::trace_closest_packets(acc, opt, set.rays.data(), set.t_max.data(),
                                 set.tile_begin.data() + b, e - b, out);
    };
  }
  return r;
}

// How many answers of two rt2 runners differ in any bit (hit t, u, v, primitive, or
// occlusion): the packets must give the single rays' answers exactly.
inline std::size_t bitwise_differences(const Runner& a, const Runner& b) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.answers.hits.size(); ++i) {
    const Hit &x = a.answers.hits[i], &y = b.answers.hits[i];
    n += std::memcmp(&x.t, &y.t, sizeof(float)) || std::memcmp(&x.u, &y.u, sizeof(float)) ||
         std::memcmp(&x.v, &y.v, sizeof(float)) || x.prim != y.prim;
  }
  for (std::size_t i = 0; i < a.answers.occluded.size(); ++i)
    n += a.answers.occluded[i] != b.answers.occluded[i];
  return n;
}

}  // namespace bench
