// Morton codes (rt2/lights/morton.h) and the radix sort of their pairs (rt2/lights/radix_sort.h): bit
// layout, clamping and NaN, and the sort checked against std::stable_sort.
#include <gtest/gtest.h>

#include <omp.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "rt2/lights/morton.h"
#include "rt2/lights/radix_sort.h"

namespace rt2 {
namespace {

using Keys = std::vector<std::uint32_t>;

constexpr std::uint32_t kXBits = 0x24924924u;  // x = 1023, y = z = 0
constexpr std::uint32_t kYBits = 0x12492492u;
constexpr std::uint32_t kZBits = 0x09249249u;
constexpr std::uint32_t kAllBits = (1u << 30) - 1;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// The oracle: values reordered by a stable sort on the low key_bits of the keys.
void oracle_sort(Keys& keys, Keys& values, int key_bits) {
  const std::uint32_t mask = key_bits == 32 ? ~0u : (1u << key_bits) - 1;
  std::vector<std::size_t> order(keys.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return (keys[a] & mask) < (keys[b] & mask);
  });
  Keys k(keys.size()), v(keys.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    k[i] = keys[order[i]];
    v[i] = values[order[i]];
  }
  keys.swap(k);
  values.swap(v);
}

// "" when equal, else the first index that differs (gtest would print a million elements).
std::string first_difference(const Keys& got, const Keys& want) {
  if (got.size() != want.size())
    return "size " + std::to_string(got.size()) + " != " + std::to_string(want.size());
  const auto m = std::mismatch(got.begin(), got.end(), want.begin());
  if (m.first == got.end()) return "";
  return "at " + std::to_string(m.first - got.begin()) + ": " + std::to_string(*m.first) +
         " != " + std::to_string(*m.second);
}

// Sorts copies of (keys, values) with radix_sort_pairs and checks them against the oracle.
void expect_sorts_like_oracle(const Keys& keys, int threads, int key_bits,
                              const std::string& what) {
  Keys values(keys.size());
  std::iota(values.begin(), values.end(), 0u);  // the input order: stability shows in them
  Keys want_k = keys, want_v = values;
  oracle_sort(want_k, want_v, key_bits);
  Keys k = keys, v = values;
  radix_sort_pairs(k, v, threads, key_bits);
  const std::string info = what + ", n " + std::to_string(keys.size()) + ", threads " +
                           std::to_string(threads) + ", key_bits " + std::to_string(key_bits);
  EXPECT_EQ(first_difference(k, want_k), "") << "keys, " << info;
  EXPECT_EQ(first_difference(v, want_v), "") << "values, " << info;
}

// Keys of three kinds, all below 2^key_bits: uniform; 37 distinct values spread over the
// whole range (long runs of equal keys: stability); and keys that vary in bits 8-15 only
// (three of four passes skipped, so the pairs end in the scratch buffers).
Keys random_keys(std::size_t n, int key_bits, int kind, std::mt19937& rng) {
  const std::uint32_t mask = key_bits == 32 ? ~0u : (1u << key_bits) - 1;
  Keys pool(37);
  for (auto& p : pool) p = rng() & mask;
  Keys keys(n);
  for (auto& k : keys) {
    if (kind == 0) k = rng() & mask;
    if (kind == 1) k = pool[rng() % pool.size()];
    if (kind == 2) k = (rng() & 0xff00u) | 0x5au;
  }
  return keys;
}

TEST(RadixSort, EqualsStdStableSortOnRandomKeys) {
  std::mt19937 rng(20240601);
  for (std::size_t n : {0, 1, 2, 4095, 4096, 100'000, 1'000'003})
    for (int key_bits : {30, 32})
      for (int kind : {0, 1, 2}) {
        const Keys keys = random_keys(n, key_bits, kind, rng);
        for (int threads : {1, 2, 3, 8})
          expect_sorts_like_oracle(keys, threads, key_bits, "kind " + std::to_string(kind));
      }
}

TEST(RadixSort, SortsAlreadySortedAndReversedInput) {
  for (std::size_t n : {2, 5000, 300'000}) {
    Keys ascending(n);
    for (std::size_t i = 0; i < n; ++i) ascending[i] = std::uint32_t(i * 2654435761u >> 2);
    std::sort(ascending.begin(), ascending.end());
    const Keys descending(ascending.rbegin(), ascending.rend());
    for (int threads : {1, 2, 3}) {
      expect_sorts_like_oracle(ascending, threads, 30, "sorted");
      expect_sorts_like_oracle(descending, threads, 30, "reversed");
    }
  }
}

TEST(RadixSort, AllEqualKeysKeepTheirOrder) {
  // Every pass is skipped: the pairs never move.
  for (int threads : {1, 2}) expect_sorts_like_oracle(Keys(50'000, 0xabcdefu), threads, 32, "");
}

TEST(RadixSort, OnlyTheLowKeyBitsTakePart) {
  // Bits 30 and 31 set at random: with key_bits 30 they are ignored, so pairs equal below
  // them keep their input order.
  std::mt19937 rng(7);
  Keys keys(20'000);
  for (auto& k : keys) k = rng() & 0xc00000ffu;
  for (int threads : {1, 2}) expect_sorts_like_oracle(keys, threads, 30, "high bits");
}

TEST(RadixSort, ZeroOrNegativeThreadsUseTheHardwareThreadsAndSort) {
  std::mt19937 rng(11);
  const Keys keys = random_keys(100'000, 30, 1, rng);
  for (int threads : {0, -1}) expect_sorts_like_oracle(keys, threads, 30, "");
}

TEST(RadixSort, ConcurrentCallsOnDifferentThreadsDoNotInterfere) {
  // Each caller has its own scratch buffers; nested inside a parallel region.
  std::mt19937 rng(3);
  const Keys a = random_keys(200'000, 30, 0, rng), b = random_keys(150'000, 30, 1, rng);
  std::vector<std::string> errors(4);
#pragma omp parallel for num_threads(4)
  for (int i = 0; i < 4; ++i) {
    const Keys& keys = i % 2 ? b : a;
    Keys v(keys.size()), want_k = keys, want_v;
    std::iota(v.begin(), v.end(), 0u);
    want_v = v;
    oracle_sort(want_k, want_v, 30);
    Keys k = keys;
    radix_sort_pairs(k, v, 2, 30);
    errors[std::size_t(i)] = first_difference(k, want_k) + first_difference(v, want_v);
  }
  for (const std::string& e : errors) EXPECT_EQ(e, "");
}

TEST(RadixSort, RejectsMismatchedSizes) {
  Keys keys{3, 1, 2}, values{0, 1};
  EXPECT_THROW(radix_sort_pairs(keys, values, 1), std::invalid_argument);
  EXPECT_EQ(keys, (Keys{3, 1, 2}));  // untouched
  Keys none;
  EXPECT_THROW(radix_sort_pairs(none, values, 2, 30), std::invalid_argument);
}

TEST(RadixSort, RejectsKeyBitsOutsideOneToThirtyTwo) {
  Keys keys{3, 1}, values{0, 1};
  EXPECT_THROW(radix_sort_pairs(keys, values, 1, 0), std::invalid_argument);
  EXPECT_THROW(radix_sort_pairs(keys, values, 1, 33), std::invalid_argument);
  EXPECT_EQ(keys, (Keys{3, 1}));
}

// A box of 1024 units per axis from the origin: cell index = integer coordinate.
const Aabb kUnitCells{vec4(0.0f, 0.0f, 0.0f), vec4(1024.0f, 1024.0f, 1024.0f)};

TEST(Morton, ExpandBitsPutsBitIAtBit3I) {
  static_assert(expand_bits_10(0) == 0);
  for (std::uint32_t i = 0; i < 10; ++i) EXPECT_EQ(expand_bits_10(1u << i), 1u << (3 * i)) << i;
  EXPECT_EQ(expand_bits_10(0x3ffu), kZBits);
  EXPECT_EQ(expand_bits_10(0x155u), 0x01041041u);  // 0b0101010101
  EXPECT_EQ(expand_bits_10(0xfffffc00u), 0u);      // bits 10 and up are ignored
}

TEST(Morton, CodeInterleavesBitsXYZ) {
  EXPECT_EQ(morton_code(vec4(0.0f, 0.0f, 0.0f), kUnitCells), 0u);
  EXPECT_EQ(morton_code(vec4(1.0f, 0.0f, 0.0f), kUnitCells), 4u);  // x in bit 2
  EXPECT_EQ(morton_code(vec4(0.0f, 1.0f, 0.0f), kUnitCells), 2u);  // y in bit 1
  EXPECT_EQ(morton_code(vec4(0.0f, 0.0f, 1.0f), kUnitCells), 1u);  // z in bit 0
  // x = 011, y = 101, z = 110 -> groups (bit 2) 011, (bit 1) 101, (bit 0) 110 = 0b011101110
  EXPECT_EQ(morton_code(vec4(3.0f, 5.0f, 6.0f), kUnitCells), 238u);
  EXPECT_EQ(morton_code(vec4(512.0f, 0.0f, 0.0f), kUnitCells), 1u << 29);
  EXPECT_EQ(morton_code(vec4(0.0f, 512.0f, 0.0f), kUnitCells), 1u << 28);
  EXPECT_EQ(morton_code(vec4(1023.0f, 0.0f, 0.0f), kUnitCells), kXBits);
  EXPECT_EQ(morton_code(vec4(0.0f, 1023.0f, 0.0f), kUnitCells), kYBits);
  EXPECT_EQ(morton_code(vec4(0.0f, 0.0f, 1023.5f), kUnitCells), kZBits);
  // Cells are half-open: 2.999 is in cell 2, the w lane plays no part.
  EXPECT_EQ(morton_code(vec4(2.999f, 0.0f, 0.0f, 77.0f), kUnitCells), 32u);
  // A box off the origin: quantised relative to lo, 4 cells per unit here.
  const Aabb box{vec4(-128.0f, 10.0f, 1000.0f), vec4(128.0f, 266.0f, 1256.0f)};
  // x = 001, y = 010, z = 011 -> groups 011, 101 = 0b011101 = 29
  EXPECT_EQ(morton_code(vec4(-127.75f, 10.5f, 1000.75f), box), 29u);
}

TEST(Morton, CodeIsMonotoneAlongEachAxis) {
  const Aabb box{vec4(-3.5f, 2.0f, -100.0f), vec4(7.25f, 2.5f, 1e4f)};
  std::mt19937 rng(5);
  for (int axis = 0; axis < 3; ++axis)
    for (int trial = 0; trial < 20; ++trial) {
      vec4 p(std::uniform_real_distribution<float>(-3.5f, 7.25f)(rng),
             std::uniform_real_distribution<float>(2.0f, 2.5f)(rng),
             std::uniform_real_distribution<float>(-100.0f, 1e4f)(rng));
      const float lo = box.lo[std::size_t(axis)], hi = box.hi[std::size_t(axis)];
      const float from = lo - (hi - lo) * 0.1f, to = hi + (hi - lo) * 0.1f;
      std::uint32_t previous = 0;
      for (int i = 0; i <= 5000; ++i) {
        p[std::size_t(axis)] = from + (to - from) * float(i) / 5000.0f;
        const std::uint32_t code = morton_code(p, box);
        ASSERT_GE(code, previous) << "axis " << axis << " step " << i;
        previous = code;
      }
    }
}

TEST(Morton, CornersMapToZeroAndMax) {
  for (const Aabb& box : {kUnitCells, Aabb{vec4(-1.0f, -2.0f, -3.0f), vec4(1.0f, 2.0f, 3.0f)},
                          Aabb{vec4(1e-6f, 5e5f, -7e3f), vec4(2e-6f, 5.5e5f, 1e-3f)}}) {
    EXPECT_EQ(morton_code(box.lo, box), 0u);
    EXPECT_EQ(morton_code(box.hi, box), kAllBits);
  }
}

TEST(Morton, FlatAxisAndNaNGiveZeroOnThatAxis) {
  // y is flat: every y, inside or not, is cell 0.
  const Aabb flat{vec4(0.0f, 5.0f, 0.0f), vec4(1024.0f, 5.0f, 1024.0f)};
  EXPECT_EQ(morton_code(vec4(1023.0f, 5.0f, 1023.0f), flat), kXBits | kZBits);
  EXPECT_EQ(morton_code(vec4(1023.0f, 9.0f, 1023.0f), flat), kXBits | kZBits);
  EXPECT_EQ(morton_code(vec4(1023.0f, -9.0f, 1023.0f), flat), kXBits | kZBits);
  const Aabb point{vec4(1.0f, 2.0f, 3.0f), vec4(1.0f, 2.0f, 3.0f)};
  EXPECT_EQ(morton_code(vec4(1.0f, 2.0f, 3.0f), point), 0u);
  // A NaN coordinate is cell 0 of its axis; the others are unaffected.
  EXPECT_EQ(morton_code(vec4(kNaN, 1023.0f, 1023.0f), kUnitCells), kYBits | kZBits);
  EXPECT_EQ(morton_code(vec4(1023.0f, kNaN, 1023.0f), kUnitCells), kXBits | kZBits);
  EXPECT_EQ(morton_code(vec4(1023.0f, 1023.0f, -kNaN), kUnitCells), kXBits | kYBits);
  EXPECT_EQ(morton_code(vec4(kNaN, kNaN, kNaN), kUnitCells), 0u);
  // A NaN or empty box gives 0 on the axes it spoils.
  const Aabb nan_x{vec4(kNaN, 0.0f, 0.0f), vec4(1024.0f, 1024.0f, 1024.0f)};
  EXPECT_EQ(morton_code(vec4(1023.0f, 1023.0f, 1023.0f), nan_x), kYBits | kZBits);
  EXPECT_EQ(morton_code(vec4(1.0f, 1.0f, 1.0f), Aabb::empty()), 0u);
}

TEST(Morton, FarOutsidePointsClampToTheEdgeCells) {
  const float inf = std::numeric_limits<float>::infinity();
  const Aabb box{vec4(-1.0f, -1.0f, -1.0f), vec4(1.0f, 1.0f, 1.0f)};
  for (float far : {1e30f, 3e38f, inf}) {
    EXPECT_EQ(morton_code(vec4(far, 0.0f, 0.0f), box) & kXBits, kXBits) << far;
    EXPECT_EQ(morton_code(vec4(-far, 0.0f, 0.0f), box) & kXBits, 0u) << far;
    EXPECT_EQ(morton_code(vec4(far, far, far), box), kAllBits) << far;
    EXPECT_EQ(morton_code(vec4(-far, -far, -far), box), 0u) << far;
    EXPECT_EQ(morton_code(vec4(-far, far, -far), box), kYBits) << far;
  }
  // Just outside: the edge cells too.
  EXPECT_EQ(morton_code(vec4(1.001f, -1.001f, 1.0f), box), kXBits | kZBits);
}

// The grid (one multiplication per axis instead of a division) orders points as morton_code
// does: equal codes away from cell borders, and monotone along each axis.
TEST(Morton, GridCodesEqualMortonCodesAwayFromCellBordersAndStayMonotone) {
  Aabb box;
  box.grow(vec4(-15.0f, 0.2f, -6.0f));
  box.grow(vec4(15.0f, 9.5f, 6.0f));
  const MortonGrid grid(box);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const vec4 extent = box.extent();
  for (int k = 0; k < 100000; ++k) {
    // Cell centres: far from every border.
    const vec4 cell((rng() % 1024) + 0.5f, (rng() % 1024) + 0.5f, (rng() % 1024) + 0.5f);
    const vec4 p = box.lo + cell * (extent * (1.0f / 1024.0f));
    ASSERT_EQ(grid.code(p), morton_code(p, box)) << k;
  }
  for (int axis = 0; axis < 3; ++axis) {
    std::uint32_t last = 0;
    for (int k = 0; k <= 4096; ++k) {
      vec4 p = box.lo + vec4(0.3f, 0.6f, 0.9f) * extent;
      const float t = box.lo[axis] + extent[axis] * float(k) / 4096.0f;
      p = vec4(axis == 0 ? t : p[0], axis == 1 ? t : p[1], axis == 2 ? t : p[2]);
      const std::uint32_t c = grid.code(p);
      ASSERT_GE(c, last) << axis << " " << k;
      last = c;
    }
  }
  // NaN: cell 0; far outside: the edge cells.
  EXPECT_EQ(grid.code(vec4(std::nanf(""), 1e30f, -1e30f)), expand_bits_10(1023) << 1);
}

}  // namespace
}  // namespace rt2
