// rt2/kernel/triangle_block_intersect.h — a ray against the four triangles of a
// TriangleBlock in one SIMD pass: the thesis's fast test and the watertight test
// (Woop, Benthin and Wald 2013).
//
// Invariant: each lane computes what the one-triangle tests of geometry/triangle.h compute, in
// the same order (no FMA: the build forbids contraction), so both agree bit for bit on every
// hit, whatever the instruction set. A test is built once per ray; called on a block it gives
// the lanes hit with t in (t_min, t_max] (inclusive, so that the closest-hit walk can break
// ties by triangle index) and their t, u, v. It keeps the ray's scalars and broadcasts them
// where a block is tested, so a ray that tests no triangle pays for no broadcast.
#pragma once

#include <array>
#include <bit>

#include "rt2/kernel/kernel.h"

#include "mlib/vfloat.h"
#include "rt2/geometry/triangle.h"
#include "rt2/geometry/triangle_block.h"

namespace rt2::RT2_ISA {

using mlib::vbool4;
using mlib::vfloat4;

// Lane hits of one block: bit i of `mask` set when lane i is hit.
struct BlockHits {
  unsigned mask = 0;
  alignas(16) float t[4], u[4], v[4];
};

// Lane hits of two blocks tested together (BlockPairLanes): bit i of `mask` set when lane i
// is hit, the first block's triangles in lanes 0 ... 3 and the second's in 4 ... 7.
struct PairHits {
  unsigned mask = 0;
  alignas(32) float t[8];
};

// The nearest lane hit in a block (ties: the lowest lane, which holds the smallest index).
struct NearestHit {
  int lane = -1;
  float t, u, v;
};

// From the lanes hit and their t, u, v: the nearest, in registers; ties at equal t go to the
// smaller triangle index prim_of(lane) (within one block the lowest lane; across the two
// blocks of a pair, BlockPairLanes, either).
template <class V, class PrimOf>
MLIB_INLINE NearestHit nearest_lane(typename V::bool_type hit, V t, V u, V v, PrimOf prim_of) {
  NearestHit n;
  const V tm = select(hit, t, V::broadcast(kInfinity));
  const unsigned at = mlib::bits(hit & (tm == mlib::reduce_min(tm)));
  if (!at) return n;
  n.lane = std::countr_zero(at);
  for (unsigned m = at & (at - 1); m; m &= m - 1) {  // a tie: rare
    const int l = std::countr_zero(m);
    if (prim_of(l) < prim_of(n.lane)) n.lane = l;
  }
  alignas(32) float ts[V::size], us[V::size], vs[V::size];
  t.store(ts), u.store(us), v.store(vs);
  n.t = ts[n.lane], n.u = us[n.lane], n.v = vs[n.lane];
  return n;
}

// How the lanes of V take the triangles of a block: lane i triangle i (V = vfloat4), one
// triangle in every lane (a packet test), or the four repeated across the lanes (pairs).
enum class LaneMap { own, one, quads };

// The triangles of V's lanes, read from the block where the tests use them: a coordinate
// picked by an axis known only at run time (the watertight test's kx, ky, kz) is one load
// from the block, not an index into a copy of it that the compiler would have to keep in
// memory. v0(a), v1(a), v2(a): coordinate a of the vertices; n(a): of the normal.
template <class V, LaneMap M>
struct TriangleLanes {
  const TriangleBlock& b;
  int lane = 0;  // LaneMap::one: the triangle

  MLIB_INLINE V read(const float (&row)[TriangleBlock::kLanes]) const {
    if constexpr (M == LaneMap::own)
      return V::load(row);
    else if constexpr (M == LaneMap::one)
      return V::broadcast(row[lane]);
    else
      return V::broadcast_quad(row);
  }
  MLIB_INLINE V v0(int a) const { return read(b.v0[a]); }
  MLIB_INLINE V v1(int a) const { return read(b.v1[a]); }
  MLIB_INLINE V v2(int a) const { return read(b.v2[a]); }
  MLIB_INLINE V n(int a) const { return read(b.n[a]); }
};

// Two blocks in the eight lanes of V = vfloat8: a's triangles in lanes 0 ... 3, b's in
// 4 ... 7 (the leaf pairs of the 8- and 16-wide walks, wide_traverse.h). Read as TriangleLanes.
template <class V>
struct BlockPairLanes {
  const TriangleBlock& a;
  const TriangleBlock& b;

  MLIB_INLINE V v0(int k) const { return V::load_halves(a.v0[k], b.v0[k]); }
  MLIB_INLINE V v1(int k) const { return V::load_halves(a.v1[k], b.v1[k]); }
  MLIB_INLINE V v2(int k) const { return V::load_halves(a.v2[k], b.v2[k]); }
  MLIB_INLINE V n(int k) const { return V::load_halves(a.n[k], b.n[k]); }
};

// The x, y and z of one ray's point or direction, each in every lane of V.
template <class V>
MLIB_INLINE std::array<V, 3> broadcast_xyz(const vec4& p) {
  return {V::broadcast(p[0]), V::broadcast(p[1]), V::broadcast(p[2])};
}

// The thesis's test (formula 10) for the lanes of V, each lane one (triangle, ray) pair,
// computing what `intersect` (triangle.h) computes. Shared by the four-triangle test below
// (four triangles, one ray) and the packet test (triangle_packet_intersect.h: one triangle,
// N rays), so both compute the same values, bit for bit. A ray parallel to a triangle
// divides by zero and fails every comparison; an empty lane (NaN) likewise. N is the
// triangle's own (Triangle::n), as `intersect` reads it.
//
// Most lanes miss, and most are rejected before any division: u >= 0 and v >= 0 are sign
// tests of S·E2 and S·E1 against Dir·N (the same tests `intersect` makes), and u + v <= 1
// and the t interval are checked in the undivided form with a relative slack of 2^-20 that
// makes the check a superset of the divided one. Lanes that survive are divided and tested
// exactly.
template <class V>
struct FastTerms {
  V tn, su, sv, den;  // T·N, S·E2, S·E1, Dir·N

  // tri: TriangleLanes or BlockPairLanes.
  template <class Tri>
  MLIB_INLINE FastTerms(const Tri& tri, const V* org, const V* dir) {
    V e1[3], e2[3], tv[3], n[3];
    for (int a = 0; a < 3; ++a) {
      const V v0 = tri.v0(a);
      e1[a] = v0 - tri.v1(a);   // E1 = V0 - V1
      e2[a] = tri.v2(a) - v0;   // E2 = V2 - V0
      tv[a] = v0 - org[a];      // T = V0 - P
      n[a] = tri.n(a);
    }
    // S = T x Dir
    const V s[3] = {tv[1] * dir[2] - tv[2] * dir[1], tv[2] * dir[0] - tv[0] * dir[2],
                    tv[0] * dir[1] - tv[1] * dir[0]};
    const auto dot = [](const V* p, const V* q) { return (p[0] * q[0] + p[1] * q[1]) + p[2] * q[2]; };
    den = dot(dir, n);
    su = dot(s, e2);
    sv = dot(s, e1);
    tn = dot(tv, n);
  }

  // The lanes that may hit with t in (t_min, t_max] (a superset of those that do).
  MLIB_INLINE unsigned may_hit(V t_min, V t_max) const {
    const V zero = V::broadcast(0.0f);
    const V u = mlib::xor_sign(su, den), v = mlib::xor_sign(sv, den);
    const V t = mlib::xor_sign(tn, den), ad = mlib::abs(den);
    const V up = V::broadcast(1.0f + 0x1p-20f), down = V::broadcast(1.0f - 0x1p-20f);
    return mlib::bits((u >= zero) & (v >= zero) & (u + v <= ad * up) &
                      (t > t_min * ad * down) & (t <= t_max * ad * up));
  }

  // The exact test: the lanes hit with t in (t_min, t_max], and their t, u, v.
  MLIB_INLINE typename V::bool_type exact(V t_min, V t_max, V& t, V& u, V& v) const {
    const V zero = V::broadcast(0.0f);
    t = tn / den;
    u = su / den;
    v = sv / den;
    return (mlib::xor_sign(su, den) >= zero) & (mlib::xor_sign(sv, den) >= zero) &
           (t > t_min) & (t <= t_max) & (u + v <= V::broadcast(1.0f));
  }
};

// The queries on two blocks at once (BlockPairLanes) that the 8- and 16-wide walks make,
// for a test that defines pair(a, b, t_min, t_max, t, u, v): the lanes hit, with their t,
// u, v (FastTriangleTest, WatertightTriangleTest).
template <class Test>
struct PairQueries {
  // The nearest lane hit of blocks a and b, a's triangles in lanes 0 ... 3 and b's in
  // 4 ... 7 (V = vfloat8), with t in (t_min, t_max].
  template <class V>
  MLIB_INLINE NearestHit nearest_pair(const TriangleBlock& a, const TriangleBlock& b, V t_min,
                                      V t_max) const {
    V t, u, v;
    const auto hit = static_cast<const Test&>(*this).pair(a, b, t_min, t_max, t, u, v);
    if (!mlib::bits(hit)) return {};
    return nearest_lane(hit, t, u, v, [&a, &b](int l) { return (l < 4 ? a : b).prim_of(l & 3); });
  }

  // Every lane of blocks a and b hit with t in (t_min, t_max], and its t.
  template <class V>
  MLIB_INLINE PairHits pair_hits(const TriangleBlock& a, const TriangleBlock& b, V t_min,
                                 V t_max) const {
    PairHits h;
    V t, u, v;
    h.mask = mlib::bits(static_cast<const Test&>(*this).pair(a, b, t_min, t_max, t, u, v));
    if (h.mask) t.store(h.t);
    return h;
  }
};

// The fast test of one ray against the four triangles of a block.
struct FastTriangleTest : PairQueries<FastTriangleTest> {
  Ray ray;

  FastTriangleTest() = default;  // unset, to be assigned (an array of per-ray tests)
  // Copied half by half: a ray just made and stored as two halves (an instance's, kernel/
  // instances.h) read back whole is a load no store can forward.
  explicit FastTriangleTest(const Ray& r) : ray(r.org, r.dir) {}

  // The undivided quantities, and the lanes that may hit in (t_min, t_max].
  struct Undivided {
    FastTerms<vfloat4> terms;
    unsigned may_hit;
  };

  MLIB_INLINE Undivided undivided(const TriangleBlock& b, vfloat4 t_min, vfloat4 t_max) const {
    // Built in place and returned as one object: returning `{terms, terms.may_hit(...)}`
    // makes GCC 12 copy the terms through memory.
    const auto org = broadcast_xyz<vfloat4>(ray.org), dir = broadcast_xyz<vfloat4>(ray.dir);
    Undivided d{
        FastTerms<vfloat4>(TriangleLanes<vfloat4, LaneMap::own>{b}, org.data(), dir.data()), 0};
    d.may_hit = d.terms.may_hit(t_min, t_max);
    return d;
  }

  // The exact test of the lanes in d.may_hit: t in (t_min, t_max], u, v.
  MLIB_INLINE static vbool4 exact(const Undivided& d, vfloat4 t_min, vfloat4 t_max, vfloat4& t,
                                  vfloat4& u, vfloat4& v) {
    return d.terms.exact(t_min, t_max, t, u, v);
  }

  // Every lane hit with t in (t_min, t_max].
  MLIB_INLINE BlockHits operator()(const TriangleBlock& b, vfloat4 t_min, vfloat4 t_max) const {
    BlockHits h;
    const Undivided d = undivided(b, t_min, t_max);
    if (!d.may_hit) return h;
    vfloat4 t, u, v;
    h.mask = mlib::bits(exact(d, t_min, t_max, t, u, v));
    t.store(h.t), u.store(h.u), v.store(h.v);
    return h;
  }

  // The nearest lane hit with t in (t_min, t_max].
  MLIB_INLINE NearestHit nearest(const TriangleBlock& b, vfloat4 t_min, vfloat4 t_max) const {
    const Undivided d = undivided(b, t_min, t_max);
    if (!d.may_hit) return {};
    vfloat4 t, u, v;
    const vbool4 hit = exact(d, t_min, t_max, t, u, v);
    return nearest_lane(hit, t, u, v, [&b](int l) { return b.prim_of(l); });
  }

  // The lanes of blocks a and b hit with t in (t_min, t_max], a's triangles in lanes
  // 0 ... 3 and b's in 4 ... 7 (V = vfloat8), and their t, u, v (unset when none is hit).
  template <class V>
  MLIB_INLINE typename V::bool_type pair(const TriangleBlock& a, const TriangleBlock& b,
                                         V t_min, V t_max, V& t, V& u, V& v) const {
    const auto o = broadcast_xyz<V>(ray.org), d = broadcast_xyz<V>(ray.dir);
    const FastTerms<V> terms(BlockPairLanes<V>{a, b}, o.data(), d.data());
    if (!terms.may_hit(t_min, t_max)) return V::bool_type::from_bits(0);
    return terms.exact(t_min, t_max, t, u, v);
  }
};

// The watertight test of Woop, Benthin and Wald (JCGT 2013) for the lanes of V, each lane
// one (triangle, ray) pair sharing the axis order kx, ky, kz: the same shear (WatertightRay)
// and edge functions as intersect_watertight, with its double precision re-evaluation for
// a lane whose edge function is exactly zero (it reads the triangles' vertices, not their
// normals). org is indexed by axis; sx, sy, sz are the rays' shear. Shared by the
// four-triangle test below and the packet test (triangle_packet_intersect.h), so both
// compute the same values, bit for bit. Returns the lanes hit with t in (t_min, t_max], with
// their t, u, v (unset when no lane is hit).
template <class V>
struct WatertightLanes {
  // The edge functions U, V, W of every lane recomputed in double precision (the paper's
  // fallback for lanes with an edge function exactly 0). Out of line and returned by value:
  // the common path keeps its edge functions in registers.
  struct Edges {
    V u, v, w;
  };
  [[gnu::noinline]] static Edges in_double(V ax, V ay, V bx, V by, V cx, V cy) {
    constexpr int n = V::size;
    alignas(64) float Ax[n], Ay[n], Bx[n], By[n], Cx[n], Cy[n], U[n], W[n], Vv[n];
    ax.store(Ax), ay.store(Ay), bx.store(Bx), by.store(By), cx.store(Cx), cy.store(Cy);
    for (int l = 0; l < n; ++l) {
      U[l] = static_cast<float>(double(Cx[l]) * By[l] - double(Cy[l]) * Bx[l]);
      Vv[l] = static_cast<float>(double(Ax[l]) * Cy[l] - double(Ay[l]) * Cx[l]);
      W[l] = static_cast<float>(double(Bx[l]) * Ay[l] - double(By[l]) * Ax[l]);
    }
    return {V::load(U), V::load(Vv), V::load(W)};
  }

  template <class Tri>  // TriangleLanes or BlockPairLanes
  MLIB_INLINE static typename V::bool_type test(const Tri& tri, const V* org,
                                                V sx, V sy, V sz, int kx, int ky, int kz,
                                                V t_min, V t_max, V& t, V& u, V& v) {
    // Vertices relative to the origin, in the ray's permuted axes.
    const V az_ = tri.v0(kz) - org[kz];
    const V bz_ = tri.v1(kz) - org[kz];
    const V cz_ = tri.v2(kz) - org[kz];
    // ... and sheared into the ray's 2D frame.
    const V ax = (tri.v0(kx) - org[kx]) - sx * az_;
    const V ay = (tri.v0(ky) - org[ky]) - sy * az_;
    const V bx = (tri.v1(kx) - org[kx]) - sx * bz_;
    const V by = (tri.v1(ky) - org[ky]) - sy * bz_;
    const V cx = (tri.v2(kx) - org[kx]) - sx * cz_;
    const V cy = (tri.v2(ky) - org[ky]) - sy * cz_;
    V eu = cx * by - cy * bx;
    V ev = ax * cy - ay * cx;
    V ew = bx * ay - by * ax;
    const V zero = V::broadcast(0.0f);
    const auto on_edge = (eu == zero) | (ev == zero) | (ew == zero);
    if (mlib::bits(on_edge)) {  // those lanes' three edge functions in double
      const Edges d = in_double(ax, ay, bx, by, cx, cy);
      eu = select(on_edge, d.u, eu);
      ev = select(on_edge, d.v, ev);
      ew = select(on_edge, d.w, ew);
    }
    const auto outside = ((eu < zero) | (ev < zero) | (ew < zero)) &
                         ((eu > zero) | (ev > zero) | (ew > zero));
    const V det = (eu + ev) + ew;
    const auto ok = andnot(outside, det != zero) & (det == det);  // not parallel, not NaN
    if (!mlib::bits(ok)) return ok;
    const V inv = V::broadcast(1.0f) / det;
    t = ((eu * (sz * az_) + ev * (sz * bz_)) + ew * (sz * cz_)) * inv;
    u = ev * inv;
    v = ew * inv;
    return ok & (t > t_min) & (t <= t_max);
  }
};

// The watertight test of one ray against the four triangles of a block.
struct WatertightTriangleTest : PairQueries<WatertightTriangleTest> {
  WatertightRay ray;

  WatertightTriangleTest() = default;  // unset, to be assigned
  explicit WatertightTriangleTest(const Ray& r) : ray(r) {}

  // Every lane hit with t in (t_min, t_max].
  MLIB_INLINE BlockHits operator()(const TriangleBlock& b, vfloat4 t_min, vfloat4 t_max) const {
    BlockHits h;
    vfloat4 t, u, v;
    h.mask = mlib::bits(test(b, t_min, t_max, t, u, v));
    if (h.mask) t.store(h.t), u.store(h.u), v.store(h.v);
    return h;
  }

  // The nearest lane hit with t in (t_min, t_max].
  MLIB_INLINE NearestHit nearest(const TriangleBlock& b, vfloat4 t_min, vfloat4 t_max) const {
    vfloat4 t, u, v;
    const vbool4 hit = test(b, t_min, t_max, t, u, v);
    if (!mlib::bits(hit)) return {};
    return nearest_lane(hit, t, u, v, [&b](int l) { return b.prim_of(l); });
  }

  // The lanes of blocks a and b hit (see FastTriangleTest::pair).
  template <class V>
  MLIB_INLINE typename V::bool_type pair(const TriangleBlock& a, const TriangleBlock& b,
                                         V t_min, V t_max, V& t, V& u, V& v) const {
    return WatertightLanes<V>::test(BlockPairLanes<V>{a, b}, broadcast_xyz<V>(ray.org).data(),
                                    V::broadcast(ray.sx),
                                    V::broadcast(ray.sy), V::broadcast(ray.sz), ray.kx, ray.ky,
                                    ray.kz, t_min, t_max, t, u, v);
  }

 private:
  MLIB_INLINE vbool4 test(const TriangleBlock& b, vfloat4 t_min, vfloat4 t_max, vfloat4& t,
                          vfloat4& u, vfloat4& v) const {
    return WatertightLanes<vfloat4>::test(TriangleLanes<vfloat4, LaneMap::own>{b},
                                          broadcast_xyz<vfloat4>(ray.org).data(),
                                          vfloat4::broadcast(ray.sx), vfloat4::broadcast(ray.sy),
                                          vfloat4::broadcast(ray.sz), ray.kx, ray.ky, ray.kz,
                                          t_min, t_max, t, u, v);
  }
};

}  // namespace rt2::RT2_ISA
