// rt2/trace.cpp — the batch queries of trace.h, on the per-ray templates of accel.h.
//
// Like the renderer (render.cpp), each call runs the loop compiled for what the Accel
// holds: a triangle mesh alone gets a loop with no sphere test and no plane loop, and the
// triangle test is a compile-time choice. Every loop answers exactly as the one over all
// primitive kinds (F = kTriangles | kSpheres | kPlanes) would: a kind the Accel does not
// hold has nothing to hit.
#include "rt2/trace.h"

#include <vector>

namespace rt2 {
namespace {

template <unsigned F>
void closest_loop(const Accel& acc, const Ray* rays, const float* t_max, std::size_t n,
                  Hit* hits) {
  for (std::size_t i = 0; i < n; ++i) hits[i] = closest_hit<F>(acc, rays[i], 0.0f, t_max[i]);
}

template <unsigned F>
void occluded_loop(const Accel& acc, const Ray* rays, const float* t_max, std::size_t n,
                   std::uint8_t* occluded) {
  static_assert(!has_feature<F, kRefraction>, "every surface is opaque: no material is read");
  static const std::vector<Material> no_materials;
  for (std::size_t i = 0; i < n; ++i)
    occluded[i] = transmittance<F>(acc, no_materials, rays[i], 0.0f, t_max[i]) == 0.0f;
}

// The feature bits of the loop for `acc` and `options`.
unsigned loop_features(const Accel& acc, const TraceOptions& options) {
  return kTriangles | (acc.spheres.empty() ? 0u : unsigned(kSpheres)) |
         (acc.planes.empty() ? 0u : unsigned(kPlanes)) |
         (options.watertight ? unsigned(kWatertight) : 0u);
}

// Calls body.template operator()<F>() with the compile-time F equal to `f` (one of the
// eight combinations loop_features returns).
template <class Body>
void dispatch(unsigned f, Body&& body) {
  constexpr unsigned T = kTriangles, S = kSpheres, P = kPlanes, W = kWatertight;
  switch (f) {
    case T: return body.template operator()<T>();
    case T | S: return body.template operator()<T | S>();
    case T | P: return body.template operator()<T | P>();
    case T | S | P: return body.template operator()<T | S | P>();
    case T | W: return body.template operator()<T | W>();
    case T | S | W: return body.template operator()<T | S | W>();
    case T | P | W: return body.template operator()<T | P | W>();
    default: return body.template operator()<T | S | P | W>();
  }
}

template <class V>
std::size_t bytes(const std::vector<V>& v) {
  return v.size() * sizeof(V);
}

}  // namespace

void trace_closest(const Accel& acc, const TraceOptions& options, const Ray* rays,
                   const float* t_max, std::size_t n, Hit* hits) {
  dispatch(loop_features(acc, options),
           [&]<unsigned F>() { closest_loop<F>(acc, rays, t_max, n, hits); });
}

void trace_occluded(const Accel& acc, const TraceOptions& options, const Ray* rays,
                    const float* t_max, std::size_t n, std::uint8_t* occluded) {
  dispatch(loop_features(acc, options),
           [&]<unsigned F>() { occluded_loop<F>(acc, rays, t_max, n, occluded); });
}

std::size_t accel_bytes(const Accel& acc) {
  return bytes(acc.bvh.nodes) + bytes(acc.bvh.order) + bytes(acc.refs) + bytes(acc.tris) +
         bytes(acc.spheres) + bytes(acc.planes);
}

}  // namespace rt2
