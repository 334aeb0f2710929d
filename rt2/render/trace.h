// rt2/render/trace.h — the kernel's ray queries for tests and benchmarks: arrays of rays
// traced with the Accel's instruction set (rt2/base/isa.h) and the chosen triangle test, one
// table lookup per call (trace_kernels.h), none per ray. The renderer's kernel makes the same
// queries inline (rt2/kernel/). They run in the calling thread's floating-point mode; callers
// that want Embree's conditions set FTZ / DAZ first (mlib/fpmode.h), as the renderer does.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "rt2/bvh/accel.h"
#include "rt2/scene/material.h"

namespace rt2 {

class Renderer;
struct Tile;

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
// walked together, 16 rays at a time (rt2/kernel/packet_traverse.h) when their directions
// allow it, else one by one. The answers are those of trace_closest / trace_occluded /
// trace_transmittance, bit for bit.
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

// The packet queries as the render kernel makes them on its batches' columns: the rays
// first + l of `rays` for the lanes l of `lanes` (one packet of at most 16), into hits[l] /
// passed[l]; the columns and t_max are read at 16 entries whatever the lanes. The answers
// are those of trace_closest / trace_transmittance, bit for bit.
void trace_closest_columns(const Accel& acc, const TraceOptions& options, const RayColumns& rays,
                           std::size_t first, std::uint32_t lanes, const float* t_max,
                           Hit* hits);
void trace_transmittance_columns(const Accel& acc, const std::vector<Material>& materials,
                                 const TraceOptions& options, const RayColumns& rays,
                                 std::size_t first, std::uint32_t lanes, const float* t_max,
                                 float* passed);

// The render kernel's first stage with `isa`'s kernel: the primary rays of samples [s0, s1)
// of the pixels of `block` (block.pixels() x (s1 - s0) of them) into rays, and their sample
// indices into samples, in batch order (for tests that hold it to Camera::ray).
void primary_rays(Isa isa, const Renderer& r, const Tile& block, int s0, int s1, Ray* rays,
                  std::uint32_t* samples);

// One ray: the closest hit in (0, t_max), and whether anything lies in (0, t_max).
Hit trace_closest(const Accel& acc, const Ray& ray, float t_max = kInfinity,
                  const TraceOptions& options = {});
bool trace_occluded(const Accel& acc, const Ray& ray, float t_max,
                    const TraceOptions& options = {});

// Bytes the acceleration structure occupies (Accel::bvh_bytes).
std::size_t accel_bytes(const Accel& acc);

}  // namespace rt2
