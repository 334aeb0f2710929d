// rt2/render/trace_kernels.h — the table behind render/trace.h: the kernel's queries compiled
// for one instruction set (rt2/kernel/trace_kernels.cpp defines one per set), each indexed
// by the triangle test ([0] fast, [1] watertight).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "rt2/base/isa.h"
#include "rt2/geometry/ray.h"

namespace rt2 {

struct Accel;
struct Material;
class Renderer;
struct Tile;
struct TraversalCounts;

struct TraceKernels {
  using Closest = void (*)(const Accel&, const Ray* rays, const float* t_max, std::size_t n,
                           Hit* hits, TraversalCounts* counts);
  using Occluded = void (*)(const Accel&, const Ray* rays, const float* t_max, std::size_t n,
                            std::uint8_t* occluded, TraversalCounts* counts);
  using Transmittance = void (*)(const Accel&, const std::vector<Material>&, const Ray* rays,
                                 const float* t_max, std::size_t n, float* passed,
                                 TraversalCounts* counts);
  using ClosestPackets = void (*)(const Accel&, const Ray* rays, const float* t_max,
                                  const std::uint32_t* packet_begin, std::size_t packets,
                                  Hit* hits, TraversalCounts* counts);
  using OccludedPackets = void (*)(const Accel&, const Ray* rays, const float* t_max,
                                   const std::uint32_t* packet_begin, std::size_t packets,
                                   std::uint8_t* occluded, TraversalCounts* counts);
  using TransmittancePackets = void (*)(const Accel&, const std::vector<Material>&,
                                        const Ray* rays, const float* t_max,
                                        const std::uint32_t* packet_begin, std::size_t packets,
                                        float* passed, TraversalCounts* counts);
  using ClosestColumns = void (*)(const Accel&, const RayColumns& rays, std::size_t first,
                                  std::uint32_t lanes, const float* t_max, Hit* hits);
  using TransmittanceColumns = void (*)(const Accel&, const std::vector<Material>&,
                                        const RayColumns& rays, std::size_t first,
                                        std::uint32_t lanes, const float* t_max, float* passed);
  using PrimaryRays = void (*)(const Renderer&, const Tile& block, int s0, int s1, Ray* rays,
                               std::uint32_t* samples);

  Isa isa;
  Closest closest[2];
  Occluded occluded[2];
  Transmittance transmittance[2];
  ClosestPackets closest_packets[2];
  OccludedPackets occluded_packets[2];
  TransmittancePackets transmittance_packets[2];
  ClosestColumns closest_columns[2];
  TransmittanceColumns transmittance_columns[2];
  PrimaryRays primary_rays;
};

// The table of `isa`, which must be one of built_isas().
const TraceKernels& trace_kernels(Isa isa);

}  // namespace rt2
