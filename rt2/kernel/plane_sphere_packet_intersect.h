// rt2/kernel/plane_sphere_packet_intersect.h — a plane or a sphere against N rays of a
// packet at once (structure of arrays).
//
// Invariant: each lane computes what the one-ray tests of geometry/plane.h and sphere.h
// compute, bit for bit: the same operations in the same order, vec4's dot product summed as
// (x x' + y y') + (z z' + w w') with the primitives' own w terms and the rays' w taken as +0
// (geometry/ray.h's invariant; rays that break it are tested one by one). A sphere's lanes
// that the one-ray test sends to double precision are reported, not computed: the caller
// runs the one-ray test for them.
#pragma once

#include "rt2/kernel/kernel.h"

#include "mlib/vfloat.h"
#include "rt2/geometry/plane.h"
#include "rt2/geometry/sphere.h"

namespace rt2::RT2_ISA {

// N rays: origins and directions per axis (w = 0 implied).
template <class V>
struct RayLanes {
  V o[3], d[3];
};

// vec4's dot of (a, 0) and (b, 0) given the products of the w lanes (wa x wb): the dpps
// order (a_x b_x + a_y b_y) + (a_z b_z + w).
template <class V>
MLIB_INLINE V dot_dpps(const V* a, const V* b, V w) {
  return (a[0] * b[0] + a[1] * b[1]) + (a[2] * b[2] + w);
}

// -x, the sign flipped (as unary minus; 0 - x differs for zeros).
template <class V>
MLIB_INLINE V negate(V x) {
  return xor_sign(x, V::broadcast(-0.0f));
}

// t of each lane where its ray meets the plane: t = -(P·N + D) / (Dir·N), as intersect()
// in plane.h (the caller applies its interval test).
template <class V>
MLIB_INLINE V plane_t(const Plane& pl, const RayLanes<V>& r) {
  const V n[3] = {V::broadcast(pl.n[0]), V::broadcast(pl.n[1]), V::broadcast(pl.n[2])};
  const V zero = V::broadcast(0.0f), w = zero * V::broadcast(pl.n[3]);
  const V denom = dot_dpps(r.d, n, w);
  return negate(dot_dpps(r.o, n, w) + V::broadcast(pl.d)) / denom;
}

// The two roots of each lane's ray with a sphere, as intersect() in sphere.h computes them
// before its interval tests: `real` where the discriminant is >= 0, `doubled` where the
// one-ray test would switch to double precision (lo and hi are then meaningless).
template <class V>
struct SphereRoots {
  V lo, hi;
  unsigned real, doubled;
};

template <class V>
MLIB_INLINE SphereRoots<V> sphere_roots(const Sphere& s, const RayLanes<V>& r) {
  const V zero = V::broadcast(0.0f);
  V oc[3];
  for (int a = 0; a < 3; ++a) oc[a] = r.o[a] - V::broadcast(s.center[a]);
  const V oc_w = zero - V::broadcast(s.center[3]);
  const float r2_s = s.radius * s.radius;
  const V r2 = V::broadcast(r2_s);
  const V oc2 = dot_dpps(oc, oc, oc_w * oc_w);
  SphereRoots<V> out;
  out.doubled = mlib::bits(V::broadcast(r2_s * 1e4f) < oc2);
  const V b = dot_dpps(r.d, oc, zero * oc_w);
  V perp[3];
  for (int a = 0; a < 3; ++a) perp[a] = oc[a] - r.d[a] * b;
  const V perp_w = oc_w - zero * b;
  const V disc = r2 - dot_dpps(perp, perp, perp_w * perp_w);
  out.real = mlib::bits(disc >= zero);  // false for NaN
  const V c = oc2 - r2;
  // copysign(sqrt(disc), b): sqrt of a non-negative disc is +0 or positive.
  const V q = negate(b + xor_sign(abs(sqrt(disc)), b));
  const V t0 = c / q, t1 = q;
  const auto swap = t0 > t1;
  out.lo = select(swap, t1, t0);
  out.hi = select(swap, t0, t1);
  return out;
}

// The lanes whose t lies in (t_min, t_max).
template <class V>
MLIB_INLINE unsigned inside(V t, V t_min, V t_max) {
  return mlib::bits((t > t_min) & (t < t_max));
}

}  // namespace rt2::RT2_ISA
