// tests/mlib/vfloat_checks.h — the checks of the wide SIMD types (vfloat4, vfloat8,
// vfloat16), written once as a template: the vfloat4 tests run them in the baseline build,
// the vfloat8 and vfloat16 ones from translation units compiled for AVX2 and AVX-512
// (vfloat8_checks.cpp, vfloat16_checks.cpp), called only on a CPU that has it. They return the number of failures and describe the first in `first` (C strings
// and snprintf only: no library template is instantiated in the AVX2 unit, where the linker
// could pick its copy for the baseline code).
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>

#include "mlib/vfloat.h"

namespace mlib::test {

inline constexpr int kFirstFailureSize = 128;

template <class V>
int check_vfloat(char (&first)[kFirstFailureSize]) {
  constexpr int N = V::size;
  int failures = 0;
  first[0] = 0;
  const auto expect = [&](bool ok, const char* what, int lane = -1) {
    if (ok) return;
    if (failures++ == 0) std::snprintf(first, sizeof first, "%s (lane %d)", what, lane);
  };
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  alignas(64) float a[N], b[N], out[N];
  for (int i = 0; i < N; ++i) {
    a[i] = float(i) - 1.5f;  // -1.5 -0.5 0.5 1.5 ...
    b[i] = 0.25f * float(N - i);
  }
  const V va = V::load(a), vb = V::load(b);
  // Arithmetic, lane by lane and IEEE-exact.
  (va * vb + va / vb - vb).store(out);
  for (int i = 0; i < N; ++i)
    expect(out[i] == a[i] * b[i] + a[i] / b[i] - b[i], "arithmetic", i);
  // Comparisons, masks, select.
  expect(mlib::bits(va < vb) == [&] {
    unsigned m = 0;
    for (int i = 0; i < N; ++i) m |= unsigned(a[i] < b[i]) << i;
    return m;
  }(), "bits(a < b)");
  select(va < vb, va, vb).store(out);
  for (int i = 0; i < N; ++i) expect(out[i] == (a[i] < b[i] ? a[i] : b[i]), "select", i);
  // NaN: ordered comparisons false, != true; min/max return the second operand.
  alignas(64) float n[N];
  for (int i = 0; i < N; ++i) n[i] = i % 2 ? nan : 1.0f;
  const V vn = V::load(n);
  expect(mlib::bits(vn <= V::broadcast(2.0f)) == [] {
    unsigned m = 0;
    for (int i = 0; i < N; i += 2) m |= 1u << i;
    return m;
  }(), "NaN fails <=");
  expect(mlib::bits(vn != vn) == [] {
    unsigned m = 0;
    for (int i = 1; i < N; i += 2) m |= 1u << i;
    return m;
  }(), "NaN != NaN");
  max(vn, V::broadcast(3.0f)).store(out);
  for (int i = 0; i < N; ++i) expect(out[i] == 3.0f, "max(NaN, 3) is 3");
  // xor_sign: a * sign(s) without multiplying (-0 counts as negative).
  xor_sign(V::broadcast(2.0f), V::broadcast(-0.0f)).store(out);
  for (int i = 0; i < N; ++i) expect(out[i] == -2.0f, "xor_sign by -0");
  abs(va).store(out);
  for (int i = 0; i < N; ++i) expect(out[i] == std::fabs(a[i]), "abs");
  // reduce_min puts the smallest lane everywhere.
  reduce_min(vb).store(out);
  for (int i = 0; i < N; ++i) expect(out[i] == 0.25f, "reduce_min");
  reduce_max(vb).store(out);
  for (int i = 0; i < N; ++i) expect(out[i] == 0.25f * float(N), "reduce_max");
  // sqrt is correctly rounded, as std::sqrt.
  sqrt(abs(va) * vb).store(out);
  for (int i = 0; i < N; ++i) expect(out[i] == std::sqrt(std::fabs(a[i]) * b[i]), "sqrt", i);
  // Integer order of the bits: float order for non-negative values, negatives lowest,
  // -0 the lowest of all.
  alignas(64) float p[N], q[N];
  for (int i = 0; i < N; ++i) {
    p[i] = i % 3 == 0 ? -0.0f : (i % 3 == 1 ? 2.5f : -7.0f);
    q[i] = i % 2 ? inf : 1.0f;
  }
  imax(V::load(p), V::load(q)).store(out);
  for (int i = 0; i < N; ++i)
    expect(out[i] == (p[i] > q[i] ? p[i] : q[i]) && !std::signbit(out[i]), "imax with a non-negative", i);
  imin(V::load(p), V::broadcast(0.0f)).store(out);
  for (int i = 0; i < N; ++i)
    expect(std::bit_cast<std::uint32_t>(out[i]) == std::bit_cast<std::uint32_t>(p[i] == 2.5f ? 0.0f : p[i]),
           "imin ranks negatives and -0 lowest");
  expect(mlib::bits(ile(V::broadcast(1.0f), V::broadcast(-0.0f))) == 0, "1 <= -0 is false as integers");
  expect(mlib::bits(ile(V::broadcast(0.5f), V::broadcast(0.75f))) == (1u << N) - 1, "0.5 <= 0.75");
  // andnot, |, &.
  expect(mlib::bits(andnot(va < vb, V::broadcast(0.0f) <= V::broadcast(0.0f))) ==
             ((1u << N) - 1) - mlib::bits(va < vb),
         "andnot");
  // floor rounds toward -inf as std::floor, keeping -0, NaN and infinities; step_ulps adds
  // trunc(k) to the bits (subtracts it below 0; NaN and huge k give INT32_MIN), wrapping.
  const float odd[] = {-0.0f, 0.0f, -1.5f, 2.5f, 1e-40f, -3e38f, 8388607.5f, -8388609.0f,
                       inf, -inf, nan, 255.9f, -255.9f, 3e9f, 0.75f, -1e-30f};
  constexpr int kOdd = sizeof odd / sizeof odd[0];
  alignas(64) float f[N], k[N];
  for (int r = 0; r < kOdd * kOdd; r += N) {
    for (int i = 0; i < N; ++i) {
      f[i] = odd[(r + i) % kOdd];
      k[i] = odd[(r + i) / kOdd % kOdd];
    }
    floor(V::load(f)).store(out);
    for (int i = 0; i < N; ++i)
      expect(std::isnan(f[i]) ? std::isnan(out[i])
                              : std::bit_cast<std::uint32_t>(out[i]) == std::bit_cast<std::uint32_t>(std::floor(f[i])),
             "floor", i);
    step_ulps(V::load(f), V::load(k)).store(out);
    for (int i = 0; i < N; ++i) {
      const std::int32_t steps = k[i] >= -2147483648.0f && k[i] < 2147483648.0f
                                     ? static_cast<std::int32_t>(k[i]) : INT32_MIN;
      const auto u = static_cast<std::uint32_t>(steps);
      const std::uint32_t want = std::bit_cast<std::uint32_t>(f[i]) + (f[i] < 0.0f ? 0u - u : u);
      expect(std::bit_cast<std::uint32_t>(out[i]) == want, "step_ulps", i);
    }
  }
  // compress against the loop it stands for, under every mask (all of them up to 8 lanes,
  // a spread of them for 16), bits moved as they are (NaN payloads, -0); from_bits gives
  // the mask's lanes; loadu / storeu at an odd address.
  alignas(64) float src[N];
  for (int i = 0; i < N; ++i)
    src[i] = i % 4 == 1 ? -0.0f : (i % 4 == 3 ? std::bit_cast<float>(0x7FC00000u + unsigned(i)) : float(i + 1));
  const unsigned all = (1u << N) - 1;
  const auto check_compress = [&](unsigned m) {
    compress(V::load(src), m).store(out);
    int packed = 0;
    for (int i = 0; i < N; ++i)
      if (m >> i & 1)
        expect(std::bit_cast<std::uint32_t>(out[packed++]) == std::bit_cast<std::uint32_t>(src[i]),
               "compress", i);
    expect(mlib::bits(V::bool_type::from_bits(m)) == m, "from_bits", int(m & 0xFF));
  };
  for (unsigned m = 0; m < all; m += N <= 8 ? 1 : 97) check_compress(m);
  check_compress(all);
  // broadcast_quad repeats four floats; spread_quads puts src[ids[q]] in quad q's lanes.
  alignas(64) float sixteen[16];
  for (int i = 0; i < 16; ++i) sixteen[i] = i == 5 ? -0.0f : i == 4 ? 1e-40f : float(i * i) - 7.5f;
  V::broadcast_quad(sixteen + 3).store(out);
  for (int i = 0; i < N; ++i)
    expect(std::bit_cast<std::uint32_t>(out[i]) == std::bit_cast<std::uint32_t>(sixteen[3 + i % 4]),
           "broadcast_quad", i);
  const std::uint32_t ids[4] = {5, 15, 0, 9};
  V::spread_quads(sixteen, ids).store(out);
  for (int i = 0; i < N; ++i)
    expect(std::bit_cast<std::uint32_t>(out[i]) == std::bit_cast<std::uint32_t>(sixteen[ids[i / 4]]),
           "spread_quads", i);
  if constexpr (N == 8) {  // load_halves and from_halves: two quads, lanes 0-3 and 4-7
    const float* lo = sixteen + 4;
    const float* hi = sixteen + 12;
    V::load_halves(lo, hi).store(out);
    for (int i = 0; i < N; ++i)
      expect(std::bit_cast<std::uint32_t>(out[i]) ==
                 std::bit_cast<std::uint32_t>(i < 4 ? lo[i] : hi[i - 4]),
             "load_halves", i);
    V::from_halves(vfloat4::load(hi), vfloat4::load(lo)).store(out);
    for (int i = 0; i < N; ++i)
      expect(std::bit_cast<std::uint32_t>(out[i]) ==
                 std::bit_cast<std::uint32_t>(i < 4 ? hi[i] : lo[i - 4]),
             "from_halves", i);
  }
  if constexpr (N >= 8) {  // vfloat8 and vfloat16
    // fmadd rounds once: (1 + 2^-12)^2 - (1 + 2^-11) is 2^-24 exactly, which the product
    // rounded first would lose (to 0); and the exact sum does not overflow where the
    // product alone would.
    const float e = 1.0f + 0x1p-12f;
    const V fused = fmadd(V::broadcast(e), V::broadcast(e), V::broadcast(-(1.0f + 0x1p-11f)));
    fused.store(out);
    for (int i = 0; i < N; ++i) expect(out[i] == 0x1p-24f, "fmadd rounds once", i);
    fmadd(V::broadcast(0x1p100f), V::broadcast(0x1p28f), V::broadcast(-0x1p127f)).store(out);
    for (int i = 0; i < N; ++i) expect(out[i] == 0x1p127f, "fmadd: no overflow of the product", i);
  }
  alignas(64) float buffer[N + 1];
  for (int i = 0; i <= N; ++i) buffer[i] = float(-i);
  const V u = V::loadu(buffer + 1);
  u.storeu(buffer);  // overlapping, one float down
  for (int i = 0; i < N; ++i) expect(buffer[i] == float(-i - 1), "loadu / storeu", i);
  return failures;
}

// compress_in_order (vfloat8: the AVX2 or the AVX-512 form, whichever the calling unit was
// built for; vfloat16: AVX-512) against the plain loop it stands for: every mask of the
// lanes (of sixteen, every 7th and the full one), under permutations packed three bits a
// lane (four for sixteen lanes) at every shift an octant order uses.
// In an unnamed namespace: the AVX2 and the AVX-512 units each instantiate it for vfloat8
// with their own compress_in_order, and two bodies under one symbol would leave the
// linker to pick either.
namespace {
template <class V>  // a template, so that only the units built for V instantiate it
int check_compress_in_order(char (&first)[kFirstFailureSize]) {
  constexpr int N = V::size, bits = N == 8 ? 3 : 4;
  constexpr unsigned lane_mask = N - 1;
  int failures = 0;
  first[0] = 0;
  alignas(64) float t[N];
  alignas(64) std::uint32_t ids[N], order[N];
  for (int i = 0; i < N; ++i) {
    t[i] = 0.5f * float(i) - 1.0f;
    ids[i] = 0x80000000u | std::uint32_t(100 + i);  // the top bit set, as a leaf reference
  }
  // Eight permutations, one per field: field o of position j holds (j * (2o + 1) + o) mod N.
  for (int j = 0; j < N; ++j) {
    order[j] = 0;
    for (int o = 0; o < 8; ++o)
      order[j] |= std::uint32_t((j * (2 * o + 1) + o) & int(lane_mask)) << (bits * o);
  }
  const V vt = V::load(t);
  const auto check = [&](int o, unsigned hit) {
    alignas(64) float t_out[N];
    alignas(64) std::uint32_t id_out[N];
    const int count = compress_in_order(vt, ids, order, bits * o, hit, t_out, id_out);
    int k = 0;
    bool ok = true;
    for (int j = 0; j < N; ++j) {
      const unsigned lane = order[j] >> (bits * o) & lane_mask;
      if (!(hit >> lane & 1u)) continue;
      ok = ok && t_out[k] == t[lane] && id_out[k] == ids[lane];
      ++k;
    }
    ok = ok && count == k;
    if (!ok && failures++ == 0)
      std::snprintf(first, sizeof first, "compress_in_order: %d lanes, octant %d, mask 0x%04x",
                    N, o, hit);
  };
  const unsigned all = (1u << N) - 1;
  for (int o = 0; o < 8; ++o) {
    for (unsigned hit = 0; hit < all; hit += N == 8 ? 1 : 7) check(o, hit);
    check(o, all);
  }
  return failures;
}
}  // namespace

}  // namespace mlib::test
