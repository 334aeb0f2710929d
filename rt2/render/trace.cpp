// rt2/render/trace.cpp — the batch queries through the instruction set's table.
#include "rt2/render/trace.h"

#include "rt2/render/trace_kernels.h"

namespace rt2 {

void trace_closest(const Accel& acc, const TraceOptions& options, const Ray* rays,
                   const float* t_max, std::size_t n, Hit* hits, TraversalCounts* counts) {
  trace_kernels(acc.isa).closest[options.watertight](acc, rays, t_max, n, hits, counts);
}

void trace_occluded(const Accel& acc, const TraceOptions& options, const Ray* rays,
                    const float* t_max, std::size_t n, std::uint8_t* occluded,
                    TraversalCounts* counts) {
  trace_kernels(acc.isa).occluded[options.watertight](acc, rays, t_max, n, occluded, counts);
}

void trace_transmittance(const Accel& acc, const std::vector<Material>& materials,
                         const TraceOptions& options, const Ray* rays, const float* t_max,
                         std::size_t n, float* passed, TraversalCounts* counts) {
  trace_kernels(acc.isa).transmittance[options.watertight](acc, materials, rays, t_max, n,
                                                           passed, counts);
}

void trace_closest_packets(const Accel& acc, const TraceOptions& options, const Ray* rays,
                           const float* t_max, const std::uint32_t* packet_begin,
                           std::size_t packets, Hit* hits, TraversalCounts* counts) {
  trace_kernels(acc.isa).closest_packets[options.watertight](acc, rays, t_max, packet_begin,
                                                             packets, hits, counts);
}

void trace_occluded_packets(const Accel& acc, const TraceOptions& options, const Ray* rays,
                            const float* t_max, const std::uint32_t* packet_begin,
                            std::size_t packets, std::uint8_t* occluded,
                            TraversalCounts* counts) {
  trace_kernels(acc.isa).occluded_packets[options.watertight](acc, rays, t_max, packet_begin,
                                                              packets, occluded, counts);
}

void trace_transmittance_packets(const Accel& acc, const std::vector<Material>& materials,
                                 const TraceOptions& options, const Ray* rays,
                                 const float* t_max, const std::uint32_t* packet_begin,
                                 std::size_t packets, float* passed, TraversalCounts* counts) {
  trace_kernels(acc.isa).transmittance_packets[options.watertight](
      acc, materials, rays, t_max, packet_begin, packets, passed, counts);
}

void trace_closest_columns(const Accel& acc, const TraceOptions& options, const RayColumns& rays,
                           std::size_t first, std::uint32_t lanes, const float* t_max,
                           Hit* hits) {
  trace_kernels(acc.isa).closest_columns[options.watertight](acc, rays, first, lanes, t_max,
                                                             hits);
}

void trace_transmittance_columns(const Accel& acc, const std::vector<Material>& materials,
                                 const TraceOptions& options, const RayColumns& rays,
                                 std::size_t first, std::uint32_t lanes, const float* t_max,
                                 float* passed) {
  trace_kernels(acc.isa).transmittance_columns[options.watertight](acc, materials, rays, first,
                                                                   lanes, t_max, passed);
}

void primary_rays(Isa isa, const Renderer& r, const Tile& block, int s0, int s1, Ray* rays,
                  std::uint32_t* samples) {
  trace_kernels(isa).primary_rays(r, block, s0, s1, rays, samples);
}

Hit trace_closest(const Accel& acc, const Ray& ray, float t_max, const TraceOptions& options) {
  Hit h;
  trace_closest(acc, options, &ray, &t_max, 1, &h);
  return h;
}

bool trace_occluded(const Accel& acc, const Ray& ray, float t_max, const TraceOptions& options) {
  std::uint8_t o = 0;
  trace_occluded(acc, options, &ray, &t_max, 1, &o);
  return o != 0;
}

std::size_t accel_bytes(const Accel& acc) { return acc.bvh_bytes(); }

}  // namespace rt2
