// rt2/trace.cpp — the batch queries of trace.h, on the per-ray templates of accel.h.
//
// One loop per query and triangle test, compiled for every primitive kind (F = kTriangles |
// kSpheres | kPlanes, plus kWatertight). Loops specialised for what the Accel holds (as the
// renderer picks its kernel) measured the same within noise on a triangle mesh (bench_trace,
// bunny00, primary and incoherent rays, 1 thread): there the per-primitive kind test always
// goes the same way and the empty plane list costs one compare per ray.
#include "rt2/trace.h"

#include <vector>

namespace rt2 {
namespace {

constexpr unsigned kAllKinds = kTriangles | kSpheres | kPlanes;

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

template <class V>
std::size_t bytes(const std::vector<V>& v) {
  return v.size() * sizeof(V);
}

}  // namespace

void trace_closest(const Accel& acc, const TraceOptions& options, const Ray* rays,
                   const float* t_max, std::size_t n, Hit* hits) {
  if (options.watertight)
    closest_loop<kAllKinds | kWatertight>(acc, rays, t_max, n, hits);
  else
    closest_loop<kAllKinds>(acc, rays, t_max, n, hits);
}

void trace_occluded(const Accel& acc, const TraceOptions& options, const Ray* rays,
                    const float* t_max, std::size_t n, std::uint8_t* occluded) {
  if (options.watertight)
    occluded_loop<kAllKinds | kWatertight>(acc, rays, t_max, n, occluded);
  else
    occluded_loop<kAllKinds>(acc, rays, t_max, n, occluded);
}

std::size_t accel_bytes(const Accel& acc) {
  return bytes(acc.bvh.nodes) + bytes(acc.bvh.order) + bytes(acc.refs) + bytes(acc.tris) +
         bytes(acc.spheres) + bytes(acc.planes);
}

}  // namespace rt2
