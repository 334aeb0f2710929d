// mlib/vfloat4_scalar.h — vfloat4 / vbool4 without SIMD: the same API as vfloat4_sse41.h
// computed lane by lane in plain C++, for the scalar build (scons arch=scalar, the thesis's
// "no SIMD" baseline). Same NaN rules as the SSE instructions it mirrors: min/max return
// the second operand when either is NaN; masks are all-ones or zero per lane.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "mlib/simd.h"  // MLIB_INLINE

namespace mlib {

struct vbool4 {
  bool m[4];
  static constexpr int size = 4;
  MLIB_INLINE static vbool4 from_bits(unsigned b) {  // lane i set where bit i of b is
    return {{(b & 1) != 0, (b & 2) != 0, (b & 4) != 0, (b & 8) != 0}};
  }
};

struct vfloat4 {
  float v[4];
  static constexpr int size = 4;
  using bool_type = vbool4;

  MLIB_INLINE static vfloat4 broadcast(float s) { return {{s, s, s, s}}; }
  MLIB_INLINE static vfloat4 load(const float* p) { return {{p[0], p[1], p[2], p[3]}}; }
  MLIB_INLINE static vfloat4 loadu(const void* p) {  // any alignment
    vfloat4 r;
    std::memcpy(r.v, p, sizeof r.v);
    return r;
  }
  MLIB_INLINE void storeu(void* p) const { std::memcpy(p, v, sizeof v); }
  MLIB_INLINE static vfloat4 from_bytes(const std::uint8_t* p) {  // lane i = p[i]
    return {{float(p[0]), float(p[1]), float(p[2]), float(p[3])}};
  }
  MLIB_INLINE static vfloat4 broadcast_quad(const float* p) { return loadu(p); }  // see vfloat16_avx512.h
  // Lane i = src[ids[i / 4]] (see vfloat16_avx512.h): one ray's value in every lane.
  MLIB_INLINE static vfloat4 spread_quads(const float* src, const std::uint32_t* ids) {
    return broadcast(src[ids[0]]);
  }
  MLIB_INLINE void store(float* p) const {
    for (int i = 0; i < 4; ++i) p[i] = v[i];
  }
  MLIB_INLINE static vfloat4 from_f4(simd::f4 a) { return {{a.v[0], a.v[1], a.v[2], a.v[3]}}; }
  MLIB_INLINE simd::f4 to_f4() const { return simd::f4{{v[0], v[1], v[2], v[3]}}; }
};

namespace detail {
template <class F>
MLIB_INLINE vfloat4 lanes(F f) {
  vfloat4 r;
  for (int i = 0; i < 4; ++i) r.v[i] = f(i);
  return r;
}
template <class F>
MLIB_INLINE vbool4 lane_mask(F f) {
  vbool4 r;
  for (int i = 0; i < 4; ++i) r.m[i] = f(i);
  return r;
}
}  // namespace detail

MLIB_INLINE vfloat4 operator+(vfloat4 a, vfloat4 b) { return detail::lanes([&](int i) { return a.v[i] + b.v[i]; }); }
MLIB_INLINE vfloat4 operator-(vfloat4 a, vfloat4 b) { return detail::lanes([&](int i) { return a.v[i] - b.v[i]; }); }
MLIB_INLINE vfloat4 operator*(vfloat4 a, vfloat4 b) { return detail::lanes([&](int i) { return a.v[i] * b.v[i]; }); }
MLIB_INLINE vfloat4 operator/(vfloat4 a, vfloat4 b) { return detail::lanes([&](int i) { return a.v[i] / b.v[i]; }); }
MLIB_INLINE vfloat4 min(vfloat4 a, vfloat4 b) { return detail::lanes([&](int i) { return a.v[i] < b.v[i] ? a.v[i] : b.v[i]; }); }
MLIB_INLINE vfloat4 max(vfloat4 a, vfloat4 b) { return detail::lanes([&](int i) { return a.v[i] > b.v[i] ? a.v[i] : b.v[i]; }); }
MLIB_INLINE vfloat4 abs(vfloat4 a) {
  return detail::lanes([&](int i) { return std::bit_cast<float>(std::bit_cast<std::uint32_t>(a.v[i]) & 0x7fffffffu); });
}
MLIB_INLINE vfloat4 sqrt(vfloat4 a) { return detail::lanes([&](int i) { return std::sqrt(a.v[i]); }); }
MLIB_INLINE vfloat4 floor(vfloat4 a) { return detail::lanes([&](int i) { return std::floor(a.v[i]); }); }
MLIB_INLINE vfloat4 step_ulps(vfloat4 a, vfloat4 k) {
  const simd::f4 r = simd::step_ulps(simd::f4{{a.v[0], a.v[1], a.v[2], a.v[3]}},
                                     simd::f4{{k.v[0], k.v[1], k.v[2], k.v[3]}});
  return {{r.v[0], r.v[1], r.v[2], r.v[3]}};
}
MLIB_INLINE vfloat4 xor_sign(vfloat4 a, vfloat4 s) {
  return detail::lanes([&](int i) {
    return std::bit_cast<float>(std::bit_cast<std::uint32_t>(a.v[i]) ^
                                (std::bit_cast<std::uint32_t>(s.v[i]) & 0x80000000u));
  });
}

MLIB_INLINE vbool4 operator<(vfloat4 a, vfloat4 b) { return detail::lane_mask([&](int i) { return a.v[i] < b.v[i]; }); }
MLIB_INLINE vbool4 operator<=(vfloat4 a, vfloat4 b) { return detail::lane_mask([&](int i) { return a.v[i] <= b.v[i]; }); }
MLIB_INLINE vbool4 operator>(vfloat4 a, vfloat4 b) { return detail::lane_mask([&](int i) { return a.v[i] > b.v[i]; }); }
MLIB_INLINE vbool4 operator>=(vfloat4 a, vfloat4 b) { return detail::lane_mask([&](int i) { return a.v[i] >= b.v[i]; }); }
MLIB_INLINE vbool4 operator==(vfloat4 a, vfloat4 b) { return detail::lane_mask([&](int i) { return a.v[i] == b.v[i]; }); }
MLIB_INLINE vbool4 operator!=(vfloat4 a, vfloat4 b) { return detail::lane_mask([&](int i) { return a.v[i] != b.v[i]; }); }
MLIB_INLINE vbool4 operator&(vbool4 a, vbool4 b) { return detail::lane_mask([&](int i) { return a.m[i] && b.m[i]; }); }
MLIB_INLINE vbool4 operator|(vbool4 a, vbool4 b) { return detail::lane_mask([&](int i) { return a.m[i] || b.m[i]; }); }
MLIB_INLINE vbool4 andnot(vbool4 a, vbool4 b) { return detail::lane_mask([&](int i) { return !a.m[i] && b.m[i]; }); }

// See vfloat4_sse41.h.
namespace detail {
MLIB_INLINE std::int32_t as_int(float f) { return std::bit_cast<std::int32_t>(f); }
}  // namespace detail
MLIB_INLINE vfloat4 imin(vfloat4 a, vfloat4 b) {
  return detail::lanes([&](int i) { return detail::as_int(a.v[i]) < detail::as_int(b.v[i]) ? a.v[i] : b.v[i]; });
}
MLIB_INLINE vfloat4 imax(vfloat4 a, vfloat4 b) {
  return detail::lanes([&](int i) { return detail::as_int(a.v[i]) > detail::as_int(b.v[i]) ? a.v[i] : b.v[i]; });
}
MLIB_INLINE vbool4 ile(vfloat4 a, vfloat4 b) {
  return detail::lane_mask([&](int i) { return detail::as_int(a.v[i]) <= detail::as_int(b.v[i]); });
}

MLIB_INLINE vfloat4 select(vbool4 m, vfloat4 if_true, vfloat4 if_false) {
  return detail::lanes([&](int i) { return m.m[i] ? if_true.v[i] : if_false.v[i]; });
}
MLIB_INLINE unsigned bits(vbool4 m) {
  return unsigned(m.m[0]) | unsigned(m.m[1]) << 1 | unsigned(m.m[2]) << 2 | unsigned(m.m[3]) << 3;
}

// The lanes of `m` set, in order, moved to the lowest lanes (see vfloat16_avx512.h).
MLIB_INLINE vfloat4 compress(vfloat4 a, unsigned m) {
  vfloat4 r = vfloat4::broadcast(a.v[0]);
  int k = 0;
  for (int i = 0; i < 4; ++i)
    if (m >> i & 1) r.v[k++] = a.v[i];
  return r;
}

MLIB_INLINE vfloat4 reduce_min(vfloat4 a) {
  const vfloat4 b{{a.v[1], a.v[0], a.v[3], a.v[2]}};
  const vfloat4 m = min(a, b);
  return min(m, vfloat4{{m.v[2], m.v[3], m.v[0], m.v[1]}});
}
MLIB_INLINE vfloat4 reduce_max(vfloat4 a) {
  const vfloat4 b{{a.v[1], a.v[0], a.v[3], a.v[2]}};
  const vfloat4 m = max(a, b);
  return max(m, vfloat4{{m.v[2], m.v[3], m.v[0], m.v[1]}});
}

}  // namespace mlib
