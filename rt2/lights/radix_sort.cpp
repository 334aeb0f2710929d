// rt2/lights/radix_sort.cpp — the LSD radix sort of (key, value) pairs: one serial and one OpenMP
// path over the same passes.
#include "rt2/lights/radix_sort.h"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>

namespace rt2 {
namespace {

// 8-bit digits: 256 counters per thread fit in L1, and so do the 512 cache lines a pass
// writes into at a time (one per digit for the keys and for the values). Fewer, wider
// digits (3 passes of 10 or 11 bits for 30-bit keys) are no faster.
constexpr int kDigitBits = 8;
constexpr std::size_t kRadix = std::size_t(1) << kDigitBits;
constexpr std::size_t kParallelMin = 4096;  // smaller inputs sort on one thread
constexpr std::size_t kMinChunk = 1024;     // pairs per thread at least

// One pass: the digit is (key >> shift) & mask.
struct Pass {
  int shift;
  std::uint32_t mask;
  std::size_t digit(std::uint32_t key) const { return (key >> shift) & mask; }
};

struct Plan {
  int passes = 0;
  std::array<Pass, (32 + kDigitBits - 1) / kDigitBits> pass{};
};

// The last pass is masked to key_bits, so that higher bits never take part.
Plan make_plan(int key_bits) {
  Plan plan;
  for (int shift = 0; shift < key_bits; shift += kDigitBits) {
    const int bits = std::min(kDigitBits, key_bits - shift);
    plan.pass[std::size_t(plan.passes++)] = {shift, (std::uint32_t(1) << bits) - 1};
  }
  return plan;
}

// The buffers a sort moves the pairs through, per calling thread (see radix_sort.h).
struct Scratch {
  std::vector<std::uint32_t> keys;
  std::vector<std::uint32_t> values;
  std::vector<std::size_t> counts;  // serial: [pass][digit]; parallel: [thread][digit]
};

thread_local Scratch scratch;

// A hint that the line holding p will be written soon. The address is formed as an integer
// because p may lie past the end of the array, where pointer arithmetic is undefined; a
// prefetch never faults.
inline void prefetch_for_write(const std::uint32_t* p, std::size_t ahead) {
  __builtin_prefetch(
      reinterpret_cast<const void*>(reinterpret_cast<std::uintptr_t>(p) + ahead * sizeof(*p)), 1);
}

// Moves [begin, end) of (sk, sv) to (dk, dv), the pair with digit d to offset[d]++.
//
// Each store is preceded by a write prefetch a few pairs ahead: a store that misses asks
// for its line only when it leaves the store buffer, so with 512 scattered streams the
// buffer fills and the misses are served nearly one at a time; the prefetch asks as soon
// as the address is known, so many overlap. Much further ahead, lines arrive early and
// compete for L1. (The portable build has no write prefetch instruction; GCC emits
// prefetcht0.) Streaming stores through per-digit line buffers are not used: they would
// need intrinsics and partial-line bookkeeping.
void scatter(const std::uint32_t* sk, const std::uint32_t* sv, std::uint32_t* dk,
             std::uint32_t* dv, std::size_t begin, std::size_t end, const Pass& pass,
             std::size_t* offset) {
  constexpr std::size_t kAhead = 4;
  for (std::size_t i = begin; i < end; ++i) {
    const std::uint32_t key = sk[i];
    const std::size_t o = offset[pass.digit(key)]++;
    dk[o] = key;
    dv[o] = sv[i];
    prefetch_for_write(dk + o, kAhead);
    prefetch_for_write(dv + o, kAhead);
  }
}

// One thread: the digits of every pass are counted in a single read (they do not depend on
// the order), then each pass scatters from one buffer pair to the other. Returns whether
// the sorted pairs are in (k1, v1).
bool sort_serial(std::uint32_t* k0, std::uint32_t* v0, std::uint32_t* k1, std::uint32_t* v1,
                 std::size_t n, const Plan& plan) {
  std::vector<std::size_t>& counts = scratch.counts;
  counts.assign(std::size_t(plan.passes) * kRadix, 0);
  for (std::size_t i = 0; i < n; ++i)
    for (int p = 0; p < plan.passes; ++p)
      ++counts[std::size_t(p) * kRadix + plan.pass[std::size_t(p)].digit(k0[i])];
  bool in_1 = false;
  for (int p = 0; p < plan.passes; ++p) {
    const Pass& pass = plan.pass[std::size_t(p)];
    std::size_t* c = counts.data() + std::size_t(p) * kRadix;
    if (c[pass.digit(k0[0])] == n) continue;  // one digit for all: the pass would copy
    std::size_t sum = 0;
    for (std::size_t d = 0; d < kRadix; ++d) sum += std::exchange(c[d], sum);
    scatter(k0, v0, k1, v1, 0, n, pass, c);
    std::swap(k0, k1);
    std::swap(v0, v1);
    in_1 = !in_1;
  }
  return in_1;
}

// `threads` threads, each owning a contiguous chunk of the source in every pass. The
// counts of a chunk change from pass to pass (its pairs do), so each pass counts anew.
// Two barriers per pass: the counts are complete before anyone computes offsets, and the
// scatter is complete (and the counts read) before the next pass counts. Every thread
// makes the same skip decisions from the shared counts, so all agree on where the pairs
// are. Returns whether the sorted pairs are in (k1, v1).
bool sort_parallel(std::uint32_t* k0, std::uint32_t* v0, std::uint32_t* k1, std::uint32_t* v1,
                   std::size_t n, const Plan& plan, int threads) {
  std::vector<std::size_t>& counts = scratch.counts;
  counts.assign(std::size_t(threads) * kRadix, 0);
  std::size_t* const shared = counts.data();
  bool result_in_1 = false;
#pragma omp parallel num_threads(threads)
  {
    // OpenMP may give fewer threads than asked for (nesting, thread limits).
    const std::size_t nt = std::size_t(omp_get_num_threads());
    const std::size_t t = std::size_t(omp_get_thread_num());
    const std::size_t begin = n * t / nt, end = n * (t + 1) / nt;
    std::uint32_t *sk = k0, *sv = v0;
    std::uint32_t *dk = k1, *dv = v1;
    bool in_1 = false;
    std::array<std::size_t, kRadix> offset;
    for (int p = 0; p < plan.passes; ++p) {
      const Pass& pass = plan.pass[std::size_t(p)];
      std::array<std::size_t, kRadix> mine{};
      for (std::size_t i = begin; i < end; ++i) ++mine[pass.digit(sk[i])];
      std::copy(mine.begin(), mine.end(), shared + t * kRadix);
#pragma omp barrier
      // offset[d] = (pairs of smaller digits) + (pairs of digit d in the chunks before ours)
      bool trivial = false;
      std::size_t base = 0;
      for (std::size_t d = 0; d < kRadix; ++d) {
        std::size_t before = 0, total = 0;
        for (std::size_t u = 0; u < nt; ++u) {
          if (u == t) before = total;
          total += shared[u * kRadix + d];
        }
        offset[d] = base + before;
        base += total;
        trivial = trivial || total == n;
      }
      if (!trivial) {
        scatter(sk, sv, dk, dv, begin, end, pass, offset.data());
        std::swap(sk, dk);
        std::swap(sv, dv);
        in_1 = !in_1;
      }
#pragma omp barrier
    }
    if (t == 0) result_in_1 = in_1;
  }
  return result_in_1;
}

}  // namespace

void radix_sort_pairs(std::vector<std::uint32_t>& keys, std::vector<std::uint32_t>& values,
                      int threads, int key_bits) {
  if (keys.size() != values.size())
    throw std::invalid_argument("radix_sort_pairs: " + std::to_string(keys.size()) +
                                " keys but " + std::to_string(values.size()) + " values");
  if (key_bits < 1 || key_bits > 32)
    throw std::invalid_argument("radix_sort_pairs: key_bits must be in [1, 32], got " +
                                std::to_string(key_bits));
  const std::size_t n = keys.size();
  if (n < 2) return;
  const Plan plan = make_plan(key_bits);
  std::size_t t = threads > 0 ? std::size_t(threads)
                              : std::max<std::size_t>(1, std::thread::hardware_concurrency());
  t = n < kParallelMin ? 1 : std::min(t, n / kMinChunk);
  scratch.keys.resize(n);
  scratch.values.resize(n);
  const bool in_scratch =
      t == 1 ? sort_serial(keys.data(), values.data(), scratch.keys.data(),
                           scratch.values.data(), n, plan)
             : sort_parallel(keys.data(), values.data(), scratch.keys.data(),
                             scratch.values.data(), n, plan, int(t));
  if (in_scratch) {
    keys.swap(scratch.keys);
    values.swap(scratch.values);
  }
}

}  // namespace rt2
