// rt2/render/trace.cpp — batch ray queries through the instruction set's kernels (trace.h).
#include "rt2/render/trace.h"

#include "rt2/render/kernel_table.h"

namespace rt2 {

void trace_closest(const Accel& acc, const TraceOptions& options, const Ray* rays,
                   const float* t_max, std::size_t n, Hit* hits, TraversalCounts* counts) {
  isa_kernels(acc.isa).trace_closest[options.watertight](acc, rays, t_max, n, hits, counts);
}

void trace_occluded(const Accel& acc, const TraceOptions& options, const Ray* rays,
                    const float* t_max, std::size_t n, std::uint8_t* occluded,
                    TraversalCounts* counts) {
  isa_kernels(acc.isa).trace_occluded[options.watertight](acc, rays, t_max, n, occluded, counts);
}

void trace_closest_packets(const Accel& acc, const TraceOptions& options, const Ray* rays,
                           const float* t_max, const std::uint32_t* packet_begin,
                           std::size_t packets, Hit* hits, TraversalCounts* counts) {
  isa_kernels(acc.isa).trace_closest_packets[options.watertight](acc, rays, t_max, packet_begin,
                                                                 packets, hits, counts);
}

void trace_occluded_packets(const Accel& acc, const TraceOptions& options, const Ray* rays,
                            const float* t_max, const std::uint32_t* packet_begin,
                            std::size_t packets, std::uint8_t* occluded,
                            TraversalCounts* counts) {
  isa_kernels(acc.isa).trace_occluded_packets[options.watertight](
      acc, rays, t_max, packet_begin, packets, occluded, counts);
}

void trace_transmittance(const Accel& acc, const std::vector<Material>& materials,
                         const TraceOptions& options, const Ray* rays, const float* t_max,
                         std::size_t n, float* passed, TraversalCounts* counts) {
  isa_kernels(acc.isa).trace_transmittance[options.watertight](acc, materials, rays, t_max, n,
                                                               passed, counts);
}

void trace_transmittance_packets(const Accel& acc, const std::vector<Material>& materials,
                                 const TraceOptions& options, const Ray* rays,
                                 const float* t_max, const std::uint32_t* packet_begin,
                                 std::size_t packets, float* passed, TraversalCounts* counts) {
  isa_kernels(acc.isa).trace_transmittance_packets[options.watertight](
      acc, materials, rays, t_max, packet_begin, packets, passed, counts);
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
