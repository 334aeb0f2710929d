// rt2/kernel/trace_kernels.cpp — the queries' table behind render/trace.h (for tests and
// benchmarks) for the instruction set this copy is compiled for: arrays of rays, packets
// and batch columns through the kernel's queries, and the primary rays of a block.
#include "rt2/kernel/kernel.h"

#include <algorithm>

#include "rt2/kernel/any_hit.h"
#include "rt2/kernel/closest_hit.h"
#include "rt2/kernel/generate.h"
#include "rt2/kernel/transmittance.h"
#include "rt2/render/trace_kernels.h"

namespace rt2::RT2_ISA {

namespace {

template <bool Watertight>
void trace_closest(const Accel& acc, const Ray* rays, const float* t_max, std::size_t n,
                   Hit* hits, TraversalCounts* counts) {
  for (std::size_t i = 0; i < n; ++i)
    hits[i] = closest_hit<Watertight>(acc, rays[i], 0.0f, t_max[i], counts);
}

template <bool Watertight>
void trace_occluded(const Accel& acc, const Ray* rays, const float* t_max, std::size_t n,
                    std::uint8_t* occluded_out, TraversalCounts* counts) {
  for (std::size_t i = 0; i < n; ++i)
    occluded_out[i] = occluded<Watertight>(acc, rays[i], 0.0f, t_max[i], counts) ? 1 : 0;
}

// Packet k: rays [packet_begin[k], packet_begin[k + 1]), in lanes 0, 1, ... A packet of
// more than kPacketSize rays is taken kPacketSize at a time; an empty one is skipped.
template <class F>
void for_each_packet(const std::uint32_t* packet_begin, std::size_t packets, F&& f) {
  for (std::size_t k = 0; k < packets; ++k)
    for (std::uint32_t b = packet_begin[k]; b < packet_begin[k + 1]; b += kPacketSize)
      f(b, std::min<std::uint32_t>(kPacketSize, packet_begin[k + 1] - b));
}

template <bool Watertight>
void trace_closest_packets(const Accel& acc, const Ray* rays, const float* t_max,
                           const std::uint32_t* packet_begin, std::size_t packets, Hit* hits,
                           TraversalCounts* counts) {
  for_each_packet(packet_begin, packets, [&](std::uint32_t b, std::uint32_t n) {
    closest_hit_packet<Watertight>(acc, rays + b, (1u << n) - 1, 0.0f, t_max + b, hits + b,
                                   counts);
  });
}

template <bool Watertight>
void trace_occluded_packets(const Accel& acc, const Ray* rays, const float* t_max,
                            const std::uint32_t* packet_begin, std::size_t packets,
                            std::uint8_t* occluded_out, TraversalCounts* counts) {
  for_each_packet(packet_begin, packets, [&](std::uint32_t b, std::uint32_t n) {
    const PacketMask blocked =
        occluded_packet<Watertight>(acc, rays + b, (1u << n) - 1, 0.0f, t_max + b, counts);
    for (std::uint32_t l = 0; l < n; ++l) occluded_out[b + l] = blocked >> l & 1;
  });
}

template <bool Watertight>
void trace_transmittance(const Accel& acc, const std::vector<Material>& materials,
                         const Ray* rays, const float* t_max, std::size_t n, float* passed,
                         TraversalCounts* counts) {
  for (std::size_t i = 0; i < n; ++i)
    passed[i] = transmittance<Watertight>(acc, materials, rays[i], 0.0f, t_max[i], counts);
}

template <bool Watertight>
void trace_transmittance_packets(const Accel& acc, const std::vector<Material>& materials,
                                 const Ray* rays, const float* t_max,
                                 const std::uint32_t* packet_begin, std::size_t packets,
                                 float* passed, TraversalCounts* counts) {
  for_each_packet(packet_begin, packets, [&](std::uint32_t b, std::uint32_t n) {
    transmittance_packet<Watertight>(acc, materials, rays + b, (1u << n) - 1, 0.0f, t_max + b,
                                     passed + b, counts);
  });
}

void primary_rays(const Renderer& r, const Tile& block, int s0, int s1, Ray* rays,
                  std::uint32_t* samples) {
  static thread_local Batches b;
  generate(r, block, s0, s1, b);
  for (std::size_t i = 0; i < b.rays.size(); ++i) {
    rays[i] = b.rays.ray(i);
    samples[i] = b.rays[i].sample;
  }
}

template <bool Watertight>
void trace_closest_columns(const Accel& acc, const RayColumns& rays, std::size_t first,
                           std::uint32_t lanes, const float* t_max, Hit* hits) {
  closest_hit_packet<Watertight>(acc, rays, first, lanes, 0.0f, t_max, hits);
}

template <bool Watertight>
void trace_transmittance_columns(const Accel& acc, const std::vector<Material>& materials,
                                 const RayColumns& rays, std::size_t first, std::uint32_t lanes,
                                 const float* t_max, float* passed) {
  transmittance_packet<Watertight>(acc, materials, rays, first, lanes, 0.0f, t_max, passed);
}

}  // namespace

const TraceKernels& trace_kernels() {
  static const TraceKernels table{
      kIsa,
      {&trace_closest<false>, &trace_closest<true>},
      {&trace_occluded<false>, &trace_occluded<true>},
      {&trace_transmittance<false>, &trace_transmittance<true>},
      {&trace_closest_packets<false>, &trace_closest_packets<true>},
      {&trace_occluded_packets<false>, &trace_occluded_packets<true>},
      {&trace_transmittance_packets<false>, &trace_transmittance_packets<true>},
      {&trace_closest_columns<false>, &trace_closest_columns<true>},
      {&trace_transmittance_columns<false>, &trace_transmittance_columns<true>},
      &primary_rays,
  };
  return table;
}

}  // namespace rt2::RT2_ISA
