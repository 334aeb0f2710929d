// rt2/geometry/triangle_packet_intersect.h — the triangles of a block against a packet of
// up to 16 rays (the leaves of a packet walk, bvh/packet_traverse.h).
//
// The fast test takes one triangle against N rays in one SIMD pass (triangle by triangle,
// where the four-triangle test takes one ray against four triangles): a coherent packet's
// rays mostly share the leaves they test, so the lanes stay full. It computes each
// (triangle, ray) pair with FastTerms, as the four-triangle test does, so both find the
// same hits, bit for bit. The watertight test keeps each ray's own four-triangle test
// (its shear and axis order differ from ray to ray).
//
// Both find, for each ray, the hit its own walk would keep: hits are merged with
// `replaces`, which orders them by t and then by triangle index, whatever order they are
// found in.
//
// Compiled per instruction set (rt2/isa.h): the code lives in rt2::RT2_ISA.
#pragma once

#include <bit>
#include <cstdint>

#include "mlib/vfloat.h"
#include "rt2/geometry/triangle_block_intersect.h"

namespace rt2::RT2_ISA {

inline constexpr int kPacketSize = 16;
using PacketMask = std::uint32_t;  // bit l: lane l of a packet

// Whether a hit of triangle `prim` at t replaces h: nearer, or as near and of a smaller
// index (a triangle also wins a tie against a sphere or a plane, whose tagged references
// are larger).
MLIB_INLINE bool replaces(const Hit& h, float t, std::uint32_t prim) {
  return t < h.t || (t == h.t && h.found() && prim < h.prim);
}

// The fast test over a packet whose rays are given as structure of arrays (org[a][l],
// dir[a][l]: axis a of ray l; 64-byte aligned), N rays at a time.
template <int N>
struct FastPacketTest {
  using V = mlib::vfloat<N>;
  const float (*org)[kPacketSize];
  const float (*dir)[kPacketSize];

  // The vertices of triangle `lane` of b, in every lane.
  MLIB_INLINE static void broadcast(const TriangleBlock& b, int lane, V* v0, V* v1, V* v2) {
    for (int a = 0; a < 3; ++a) {
      v0[a] = V::broadcast(b.v0[a][lane]);
      v1[a] = V::broadcast(b.v1[a][lane]);
      v2[a] = V::broadcast(b.v2[a][lane]);
    }
  }
  MLIB_INLINE void rays(int c, V* o, V* d) const {
    for (int a = 0; a < 3; ++a) {
      o[a] = V::load(org[a] + c);
      d[a] = V::load(dir[a] + c);
    }
  }

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
  // those rays.
  template <class F>
  MLIB_INLINE PacketMask for_each_hit(const TriangleBlock& b, PacketMask lanes, float t_min_s,
                                      const float* t_upper, F&& f) const {
    const V t_min = V::broadcast(t_min_s);
    PacketMask done = 0;
    for (int j = 0; j < TriangleBlock::kLanes && lanes; ++j) {
      const std::uint32_t prim = b.prim_of(j);
      if (prim == TriangleBlock::kNoPrim) break;  // empty lanes come last
      V v0[3], v1[3], v2[3];
      broadcast(b, j, v0, v1, v2);
      for (int c = 0; c < kPacketSize; c += N) {
        const unsigned chunk = lanes >> c & ((1u << N) - 1);
        if (!chunk) continue;
        V o[3], d[3];
        rays(c, o, d);
        const FastTerms<V> terms(v0, v1, v2, o, d);
        const V t_max = V::load(t_upper + c);
        unsigned m = terms.may_hit(t_min, t_max) & chunk;
        if (!m) continue;
        V t, u, v;
        m &= mlib::bits(terms.exact(t_min, t_max, t, u, v));
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

}  // namespace rt2::RT2_ISA
