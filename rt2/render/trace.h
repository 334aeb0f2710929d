// rt2/render/trace.h — batch ray queries against an Accel, for tests and benchmarks: arrays of
// rays traced with the Accel's instruction set (rt2/base/isa.h) and the chosen triangle test.
// One table lookup per call, none per ray. The renderer does not use these: its kernel
// calls the same queries inline (rt2/kernel/query.h). They run in the calling thread's
// floating-point mode; callers that want Embree's conditions set FTZ / DAZ first
// (mlib/fpmode.h), as the renderer does.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "rt2/bvh/accel.h"
#include "rt2/scene/material.h"

namespace rt2 {

struct TraceOptions {
  bool watertight = false;  // the triangle test: the thesis's fast one, or the watertight one
};

// hits[i] = the closest hit of rays[i] in (0, t_max[i]) over planes, spheres and triangles
// (miss: !found(), t = inf). `counts`, when given, accumulates nodes and blocks visited.
void trace_closest(const Accel& acc, const TraceOptions& options, const Ray* rays,
                   const float* t_max, std::size_t n, Hit* hits,
                   TraversalCounts* counts = nullptr);

// occluded[i] = 1 when any primitive lies on rays[i] in (0, t_max[i]) (every surface
// opaque), else 0.
void trace_occluded(const Accel& acc, const TraceOptions& options, const Ray* rays,
                    const float* t_max, std::size_t n, std::uint8_t* occluded,
                    TraversalCounts* counts = nullptr);

// passed[i] = the share of light that passes along rays[i] in (0, t_max[i]): 1 when nothing
// is in the way, 0 behind an opaque surface, else the product of the transparencies Kt
// (materials[...].transparency) of every surface crossed (the renderer's shadow rays).
void trace_transmittance(const Accel& acc, const std::vector<Material>& materials,
                         const TraceOptions& options, const Ray* rays, const float* t_max,
                         std::size_t n, float* passed, TraversalCounts* counts = nullptr);

// The same for packets of coherent rays (a 4 x 4 tile of primary rays, their shadow rays):
// packet k is rays [packet_begin[k], packet_begin[k + 1]) (packet_begin non-decreasing),
// walked together, 16 rays at a time, (rt2/kernel/packet_traverse.h) when their directions
// allow it, else one by one. The answers are those of trace_closest / trace_occluded / trace_transmittance, bit
// for bit.
void trace_closest_packets(const Accel& acc, const TraceOptions& options, const Ray* rays,
                           const float* t_max, const std::uint32_t* packet_begin,
                           std::size_t packets, Hit* hits, TraversalCounts* counts = nullptr);
void trace_occluded_packets(const Accel& acc, const TraceOptions& options, const Ray* rays,
                            const float* t_max, const std::uint32_t* packet_begin,
                            std::size_t packets, std::uint8_t* occluded,
                            TraversalCounts* counts = nullptr);
void trace_transmittance_packets(const Accel& acc, const std::vector<Material>& materials,
                                 const TraceOptions& options, const Ray* rays,
                                 const float* t_max, const std::uint32_t* packet_begin,
                                 std::size_t packets, float* passed,
                                 TraversalCounts* counts = nullptr);

// One ray: the closest hit in (0, t_max), and whether anything lies in (0, t_max).
Hit trace_closest(const Accel& acc, const Ray& ray, float t_max = kInfinity,
                  const TraceOptions& options = {});
bool trace_occluded(const Accel& acc, const Ray& ray, float t_max,
                    const TraceOptions& options = {});

// Bytes the acceleration structure occupies (Accel::bvh_bytes).
std::size_t accel_bytes(const Accel& acc);

}  // namespace rt2
