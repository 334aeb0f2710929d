// rt2/kernel/triangle_packet_intersect.h — the triangles of a block against a packet of up
// to 16 rays: the leaves of a packet walk (packet_traverse.h).
//
// One triangle against kRayLanes rays per SIMD pass (a coherent packet's rays share their
// leaves, so the lanes stay full), each (triangle, ray) pair computed with FastTerms or
// WatertightLanes as the four-triangle tests compute it, so every ray finds the hit of its
// own walk, bit for bit; hits are merged with `replaces` (by t, then triangle index) in any
// order. The watertight test needs the rays to share their axis order; a packet whose rays
// do not is tested ray by ray.
#pragma once

#include <bit>
#include <cstdint>
#include <utility>

#include "rt2/kernel/kernel.h"

#include "mlib/vfloat.h"
#include "rt2/kernel/triangle_block_intersect.h"

namespace rt2::RT2_ISA {

inline constexpr int kPacketSize = 16;
using PacketMask = std::uint32_t;  // bit l: lane l of a packet
// How many of a packet's rays one SIMD pass takes: the widest vfloat of the instruction set
// (16 with AVX-512: the whole packet).
inline constexpr int kRayLanes = mlib::kWidestLanes;
static_assert(kPacketSize % kRayLanes == 0);

// Whether a hit of triangle `prim` at t replaces h: nearer, or as near and of a smaller
// index (a triangle also wins a tie against a sphere or a plane, whose tagged references
// are larger).
MLIB_INLINE bool replaces(const Hit& h, float t, std::uint32_t prim) {
  return t < h.t || (t == h.t && h.found() && prim < h.prim);
}

// The fast test's arithmetic for rays c ... c + N - 1 of a packet given as structure of
// arrays (org[a][l], dir[a][l]: axis a of ray l; 64-byte aligned): FastTerms, as the
// four-triangle test computes it.
template <int N>
struct FastPacketRays {
  using V = mlib::vfloat<N>;
  const float (*org)[kPacketSize];
  const float (*dir)[kPacketSize];

  // The lanes hit by the triangle `tri` (broadcast) with t in (t_min, t_max], with their t,
  // u, v.
  template <LaneMap M>
  MLIB_INLINE unsigned hits(const TriangleLanes<V, M>& tri, int c, V t_min, V t_max, V& t, V& u,
                            V& v) const {
    V o[3], d[3];
    for (int a = 0; a < 3; ++a) {
      o[a] = V::load(org[a] + c);
      d[a] = V::load(dir[a] + c);
    }
    return test(tri, o, d, t_min, t_max, t, u, v);
  }
  // The same for pairs: lane i takes ray ids[i / 4] of the packet (and the triangle the
  // caller put in lane i).
  template <LaneMap M>
  MLIB_INLINE unsigned hits_pairs(const TriangleLanes<V, M>& tri, const std::uint32_t* ids, V t_min,
                                  V t_max, V& t, V& u, V& v) const {
    V o[3], d[3];
    for (int a = 0; a < 3; ++a) {
      o[a] = V::spread_quads(org[a], ids);
      d[a] = V::spread_quads(dir[a], ids);
    }
    return test(tri, o, d, t_min, t_max, t, u, v);
  }

 private:
  template <LaneMap M>
  MLIB_INLINE static unsigned test(const TriangleLanes<V, M>& tri, const V* o, const V* d, V t_min,
                                   V t_max, V& t, V& u, V& v) {
    const FastTerms<V> terms(tri, o, d);
    const unsigned m = terms.may_hit(t_min, t_max);
    return m ? m & mlib::bits(terms.exact(t_min, t_max, t, u, v)) : 0u;
  }
};

// The watertight test's arithmetic for rays c ... c + N - 1 of a packet whose rays share
// their axis order (WatertightRay's kx, ky, kz: the axis of the largest direction component
// and the sign of that component), each with its own shear: WatertightLanes, as the
// four-triangle test computes it.
template <int N>
struct WatertightPacketRays {
  using V = mlib::vfloat<N>;
  const float (*org)[kPacketSize] = nullptr;
  alignas(64) float sx[kPacketSize], sy[kPacketSize], sz[kPacketSize];
  int kx = 0, ky = 0, kz = 0;

  // Sets the shears up from the packet's rays, as structure of arrays (origins and
  // directions as PacketRays holds them: every lane set, those outside the packet copies of
  // one of its rays), in SIMD with WatertightRay's arithmetic; false when two rays' axis
  // orders differ.
  bool make(const float (*origins)[kPacketSize], const float (*dirs)[kPacketSize]) {
    org = origins;
    constexpr unsigned kAll = (1u << N) - 1;
    int order = -1;  // kz, and 3 more when the kz component is negative
    for (int c = 0; c < kPacketSize; c += N) {
      const V d[3] = {V::load(dirs[0] + c), V::load(dirs[1] + c), V::load(dirs[2] + c)};
      const V ax = abs(d[0]), ay = abs(d[1]), az = abs(d[2]);
      // kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2)
      const unsigned x_gt_y = mlib::bits(ax > ay);
      const unsigned z0 = x_gt_y & mlib::bits(ax > az);
      const unsigned z1 = ~x_gt_y & mlib::bits(ay > az) & kAll;
      const int kz_c = z0 == kAll ? 0 : z1 == kAll ? 1 : (z0 | z1) == 0 ? 2 : -1;
      if (kz_c < 0) return false;
      const unsigned negative = mlib::bits(d[kz_c] < V::broadcast(0.0f));
      if (negative != 0 && negative != kAll) return false;
      const int order_c = kz_c + (negative ? 3 : 0);
      if (order >= 0 && order_c != order) return false;
      order = order_c;
      kz = kz_c;
      kx = (kz + 1) % 3;
      ky = (kx + 1) % 3;
      if (negative) std::swap(kx, ky);
      (d[kx] / d[kz]).store(sx + c);
      (d[ky] / d[kz]).store(sy + c);
      (V::broadcast(1.0f) / d[kz]).store(sz + c);
    }
    return true;
  }

  template <LaneMap M>
  MLIB_INLINE unsigned hits(const TriangleLanes<V, M>& tri, int c, V t_min, V t_max, V& t, V& u,
                            V& v) const {
    V o[3];
    for (int a = 0; a < 3; ++a) o[a] = V::load(org[a] + c);
    return mlib::bits(WatertightLanes<V>::test(tri, o, V::load(sx + c), V::load(sy + c),
                                               V::load(sz + c), kx, ky, kz, t_min, t_max, t, u,
                                               v));
  }
  // The same for pairs: lane i takes ray ids[i / 4] of the packet.
  template <LaneMap M>
  MLIB_INLINE unsigned hits_pairs(const TriangleLanes<V, M>& tri, const std::uint32_t* ids, V t_min,
                                  V t_max, V& t, V& u, V& v) const {
    V o[3];
    for (int a = 0; a < 3; ++a) o[a] = V::spread_quads(org[a], ids);
    return mlib::bits(WatertightLanes<V>::test(tri, o, V::spread_quads(sx, ids),
                                               V::spread_quads(sy, ids), V::spread_quads(sz, ids),
                                               kx, ky, kz, t_min, t_max, t, u, v));
  }
};

// One triangle of a block against N rays of a packet at a time (Rays: FastPacketRays or
// WatertightPacketRays, which hold the packet's rays); when few of the packet's rays reach
// the block, N / 4 rays against its four triangles at a time instead, (ray, triangle) pairs
// in the lanes. Each pair is computed as in the other form, so both find the same hits.
template <int N, class Rays>
struct TriangleMajorPacketTest {
  using V = mlib::vfloat<N>;
  Rays rays;

  // For each ray l of `lanes`: the hits in b with t in (t_min, hits[l].t] merged into
  // hits[l] (`replaces`); t_best[l] mirrors hits[l].t (64-byte aligned).
  MLIB_INLINE void nearest(const TriangleBlock& b, PacketMask lanes, float t_min, Hit* hits,
                           float* t_best) const {
    for_each_hit(b, lanes, t_min, t_best, [&](int l, std::uint32_t prim, float t, float u,
                                              float v) {
      Hit& h = hits[l];
      if (replaces(h, t, prim)) {
        h.t = t_best[l] = t;
        h.u = u;
        h.v = v;
        h.prim = prim;
      }
      return false;
    });
  }

  // For each ray l of `lanes`: on_hit(l, prim, t) for its hits in b with t in
  // (t_min, t_below[l]] (64-byte aligned), until it returns true for the ray; returns the
  // rays for which it did.
  template <class OnHit>
  MLIB_INLINE PacketMask any(const TriangleBlock& b, PacketMask lanes, float t_min,
                             const float* t_below, OnHit& on_hit) const {
    return for_each_hit(b, lanes, t_min, t_below,
                        [&](int l, std::uint32_t prim, float t, float, float) {
                          return on_hit(l, prim, t);
                        });
  }

 private:
  // Triangle by triangle of b, N rays of `lanes` at a time: f(l, prim, t, u, v) for each
  // hit of ray l with t in (t_min, t_upper[l]], t_upper re-read for every triangle (f may
  // lower it). A ray for which f returns true is dropped after that triangle; returns
  // those rays. Or by pairs (few rays), each pass's bounds read once: a hit beyond a bound
  // that f lowered meanwhile is still offered to f, which for nearest() keeps the nearer
  // (replaces orders hits whatever the order they come in) and for any() is a hit in range.
  template <class F>
  MLIB_INLINE PacketMask for_each_hit(const TriangleBlock& b, PacketMask lanes, float t_min_s,
                                      const float* t_upper, F&& f) const {
    const V t_min = V::broadcast(t_min_s);
    PacketMask done = 0;
    if (!lanes) return done;
    // Few rays: (ray, triangle) pairs, N / 4 rays against the block's four triangles per
    // pass, when that takes fewer passes than triangle by triangle; with 8 or 16 lanes, half
    // as many at most (a pass of pairs also spreads its rays over the lanes).
    int triangles = 0;  // empty lanes come last
    while (triangles < TriangleBlock::kLanes && b.prim_of(triangles) != TriangleBlock::kNoPrim)
      ++triangles;
    int chunks = 0;
    for (int c = 0; c < kPacketSize; c += N) chunks += (lanes >> c & ((1u << N) - 1)) != 0;
    constexpr int kRaysPerPass = N / 4;
    const int pair_passes = (std::popcount(lanes) + kRaysPerPass - 1) / kRaysPerPass;
    const int triangle_passes = triangles * chunks;
    if (N == 4 ? pair_passes < triangle_passes : 2 * pair_passes <= triangle_passes) {
      const TriangleLanes<V, LaneMap::quads> tri{b};
      // The rays in order, the last repeated to fill the final pass.
      std::uint32_t ids[kPacketSize + kRaysPerPass];
      int k = 0;
      for (PacketMask m = lanes; m; m &= m - 1) ids[k++] = static_cast<std::uint32_t>(std::countr_zero(m));
      for (int j = k; j < k + kRaysPerPass; ++j) ids[j] = ids[k - 1];
      for (int p = 0; p < k; p += kRaysPerPass) {
        V t = V::broadcast(0.0f), u = t, v = t;  // set by hits() where it hits (GCC cannot tell)
        const int here = std::min(kRaysPerPass, k - p);
        // the pass's rays, and the block's triangles (its empty lanes' NaN vertices hit
        // nothing: masked all the same)
        constexpr unsigned kEveryQuad = N == 16 ? 0x1111u : N == 8 ? 0x11u : 0x1u;
        unsigned m = rays.hits_pairs(tri, ids + p, t_min, V::spread_quads(t_upper, ids + p),
                                     t, u, v) &
                     ((1u << (4 * here)) - 1) & (((1u << triangles) - 1) * kEveryQuad);
        if (!m) continue;
        alignas(64) float ts[N], us[N], vs[N];
        t.store(ts), u.store(us), v.store(vs);
        for (; m; m &= m - 1) {
          const int i = std::countr_zero(m);
          const int l = static_cast<int>(ids[p + i / 4]);
          if (done >> l & 1) continue;
          if (f(l, b.prim_of(i % 4), ts[i], us[i], vs[i])) done |= PacketMask(1) << l;
        }
      }
      return done;
    }
    for (int j = 0; j < TriangleBlock::kLanes && lanes; ++j) {
      const std::uint32_t prim = b.prim_of(j);
      if (prim == TriangleBlock::kNoPrim) break;  // empty lanes come last
      const TriangleLanes<V, LaneMap::one> tri{b, j};
      for (int c = 0; c < kPacketSize; c += N) {
        const unsigned chunk = lanes >> c & ((1u << N) - 1);
        if (!chunk) continue;
        V t = V::broadcast(0.0f), u = t, v = t;  // set by hits() where it hits (GCC cannot tell)
        unsigned m = rays.hits(tri, c, t_min, V::load(t_upper + c), t, u, v) & chunk;
        if (!m) continue;
        alignas(64) float ts[N], us[N], vs[N];
        t.store(ts), u.store(us), v.store(vs);
        for (; m; m &= m - 1) {
          const int i = std::countr_zero(m);
          if (f(c + i, prim, ts[i], us[i], vs[i])) done |= PacketMask(1) << (c + i);
        }
      }
      lanes &= ~done;
    }
    return done;
  }
};

// A packet tested ray by ray, each ray with its own four-triangle test (Test: a
// FastTriangleTest or a WatertightTriangleTest).
template <class Test>
struct RayByRayPacketTest {
  Test tests[kPacketSize];  // set for the packet's rays

  MLIB_INLINE void nearest(const TriangleBlock& b, PacketMask lanes, float t_min, Hit* hits,
                           float* t_best) const {
    const vfloat4 t_min_4 = vfloat4::broadcast(t_min);
    for (; lanes; lanes &= lanes - 1) {
      const int l = std::countr_zero(lanes);
      Hit& h = hits[l];
      const NearestHit n = tests[l].nearest(b, t_min_4, vfloat4::broadcast(h.t));
      if (n.lane < 0 || !replaces(h, n.t, b.prim_of(n.lane))) continue;
      h.t = t_best[l] = n.t;
      h.u = n.u;
      h.v = n.v;
      h.prim = b.prim_of(n.lane);
    }
  }

  template <class OnHit>
  MLIB_INLINE PacketMask any(const TriangleBlock& b, PacketMask lanes, float t_min,
                             const float* t_below, OnHit& on_hit) const {
    const vfloat4 t_min_4 = vfloat4::broadcast(t_min);
    PacketMask done = 0;
    for (; lanes; lanes &= lanes - 1) {
      const int l = std::countr_zero(lanes);
      const BlockHits bh = tests[l](b, t_min_4, vfloat4::broadcast(t_below[l]));
      for (unsigned m = bh.mask; m; m &= m - 1) {
        const int i = std::countr_zero(m);
        if (on_hit(l, b.prim_of(i), bh.t[i])) {
          done |= PacketMask(1) << l;
          break;
        }
      }
    }
    return done;
  }
};

template <int N>
using FastPacketTest = TriangleMajorPacketTest<N, FastPacketRays<N>>;

// The watertight test over a packet: triangle by triangle when the packet's rays share
// their axis order (a coherent packet nearly always does), else ray by ray.
template <int N>
struct WatertightPacketTest {
  bool shared = false;
  TriangleMajorPacketTest<N, WatertightPacketRays<N>> triangle_major;
  RayByRayPacketTest<WatertightTriangleTest> ray_by_ray;  // set only when !shared

  // origins and dirs: the packet's rays as PacketRays holds them; ray_at(l): ray l of them.
  template <class RayAt>
  WatertightPacketTest(const float (*origins)[kPacketSize], const float (*dirs)[kPacketSize],
                       RayAt&& ray_at, PacketMask lanes) {
    shared = triangle_major.rays.make(origins, dirs);
    if (shared) return;
    for (; lanes; lanes &= lanes - 1) {
      const int l = std::countr_zero(lanes);
      ray_by_ray.tests[l] = WatertightTriangleTest(ray_at(l));
    }
  }

  MLIB_INLINE void nearest(const TriangleBlock& b, PacketMask lanes, float t_min, Hit* hits,
                           float* t_best) const {
    if (shared)
      triangle_major.nearest(b, lanes, t_min, hits, t_best);
    else
      ray_by_ray.nearest(b, lanes, t_min, hits, t_best);
  }

  template <class OnHit>
  MLIB_INLINE PacketMask any(const TriangleBlock& b, PacketMask lanes, float t_min,
                             const float* t_below, OnHit& on_hit) const {
    return shared ? triangle_major.any(b, lanes, t_min, t_below, on_hit)
                  : ray_by_ray.any(b, lanes, t_min, t_below, on_hit);
  }
};

}  // namespace rt2::RT2_ISA
