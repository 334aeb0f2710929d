// rt2/render/kernel_table.h — the entry points compiled once per instruction set (rt2/base/isa.h), as a
// table of function pointers: the render kernel, and batch ray queries for tests and
// benchmarks. A Renderer or a batch call looks its table up once; nothing dispatches per
// ray.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "rt2/base/isa.h"
#include "rt2/geometry/ray.h"

namespace rt2 {

struct Accel;
struct Material;
class Film;
class Renderer;
struct RayCounts;
struct Tile;
struct TraversalCounts;

struct IsaKernels {
  // Samples [s0, s1) of a tile's pixels into a film (rt2/render/renderer.h).
  using RenderTile = void (*)(const Renderer&, const Tile&, int s0, int s1, Film&, RayCounts&);
  // hits[i] = the closest hit of rays[i] in (0, t_max[i]) (rt2/kernel/query.h).
  using TraceClosest = void (*)(const Accel&, const Ray* rays, const float* t_max,
                                std::size_t n, Hit* hits, TraversalCounts* counts);
  // occluded[i] = 1 when anything lies on rays[i] in (0, t_max[i]), every surface opaque.
  using TraceOccluded = void (*)(const Accel&, const Ray* rays, const float* t_max,
                                 std::size_t n, std::uint8_t* occluded, TraversalCounts* counts);

  // passed[i] = the share of light that passes along rays[i] in (0, t_max[i]) through the
  // surfaces' transparencies (rt2/kernel/query.h, transmittance).
  using TraceTransmittance = void (*)(const Accel&, const std::vector<Material>&,
                                      const Ray* rays, const float* t_max, std::size_t n,
                                      float* passed, TraversalCounts* counts);

  // The same over packets of at most 16 consecutive rays: packet k is rays
  // [packet_begin[k], packet_begin[k + 1]) (rt2/render/trace.h).
  using TraceClosestPackets = void (*)(const Accel&, const Ray* rays, const float* t_max,
                                       const std::uint32_t* packet_begin, std::size_t packets,
                                       Hit* hits, TraversalCounts* counts);
  using TraceOccludedPackets = void (*)(const Accel&, const Ray* rays, const float* t_max,
                                        const std::uint32_t* packet_begin, std::size_t packets,
                                        std::uint8_t* occluded, TraversalCounts* counts);
  using TraceTransmittancePackets = void (*)(const Accel&, const std::vector<Material>&,
                                             const Ray* rays, const float* t_max,
                                             const std::uint32_t* packet_begin,
                                             std::size_t packets, float* passed,
                                             TraversalCounts* counts);

  // The render kernel's stage 1 (rt2/kernel/tracer.h, generate): the primary rays of samples
  // [s0, s1) of a block's pixels (block.pixels() x (s1 - s0) of them) into rays and their
  // sample indices into samples, in batch order; for tests that hold it to Camera::ray.
  using PrimaryRays = void (*)(const Renderer&, const Tile& block, int s0, int s1, Ray* rays,
                               std::uint32_t* samples);

  // The packet queries the render kernel makes on its batches' columns (rt2/kernel/query.h): the
  // rays first + l of `rays` for the lanes l of `lanes` (one packet), into hits[l] /
  // passed[l]; the columns and t_max are read at kPacketSize (16) entries whatever the
  // lanes. For tests that hold them to the single-ray queries.
  using TraceClosestColumns = void (*)(const Accel&, const RayColumns& rays, std::size_t first,
                                       std::uint32_t lanes, const float* t_max, Hit* hits);
  using TraceTransmittanceColumns = void (*)(const Accel&, const std::vector<Material>&,
                                             const RayColumns& rays, std::size_t first,
                                             std::uint32_t lanes, const float* t_max,
                                             float* passed);

  Isa isa;
  PrimaryRays primary_rays;
  TraceClosestColumns trace_closest_columns[2];
  TraceTransmittanceColumns trace_transmittance_columns[2];
  // Each indexed by the triangle test: [0] the fast one, [1] the watertight one.
  RenderTile render_tile[2];
  TraceClosest trace_closest[2];
  TraceOccluded trace_occluded[2];
  TraceClosestPackets trace_closest_packets[2];
  TraceOccludedPackets trace_occluded_packets[2];
  TraceTransmittance trace_transmittance[2];
  TraceTransmittancePackets trace_transmittance_packets[2];
};

// The table of `isa`, which must be one of built_isas().
const IsaKernels& isa_kernels(Isa isa);

}  // namespace rt2
