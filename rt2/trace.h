// rt2/trace.h — batch ray queries against an Accel: the seam between rt2's acceleration
// structure and the programs that trace arrays of rays (benchmarks, tests).
//
// Callers see arrays in and arrays out, never the BVH layout or the traversal, so the
// structure behind an Accel can change (a wide SIMD BVH, packets, reordering inside a
// batch) without touching them. Each call is single-threaded and touches only the outputs
// [0, n) of its own call: callers parallelise by calling on disjoint sub-ranges from
// several threads at once (the Accel is only read).
//
// Rays follow ray.h: unit direction, w = 0. A ray covers the open interval (0, t_max[i]);
// t_max[i] may be +inf. A NaN t_max hits nothing. Every surface is opaque here (materials
// are not consulted).
#pragma once

#include <cstddef>
#include <cstdint>

#include "rt2/accel.h"
#include "rt2/ray.h"

namespace rt2 {

struct TraceOptions {
  // Triangle test: false = the thesis's fast test, true = the watertight test
  // (geometry/triangle.h). Spheres and planes have one test each.
  bool watertight = false;
};

// hits[i] = the closest hit of rays[i] in (0, t_max[i]) over planes, spheres and triangles
// (Hit as in ray.h: t, triangle barycentrics u, v and the PrimRef; a miss is !found(), with
// t = +inf).
void trace_closest(const Accel& acc, const TraceOptions& options, const Ray* rays,
                   const float* t_max, std::size_t n, Hit* hits);

// occluded[i] = 1 when any primitive lies on rays[i] in (0, t_max[i]), else 0. Stops at the
// first hit found, which need not be the closest.
void trace_occluded(const Accel& acc, const TraceOptions& options, const Ray* rays,
                    const float* t_max, std::size_t n, std::uint8_t* occluded);

// Bytes the acceleration structure occupies, for bytes per triangle: BVH nodes, the leaf
// order, the leaf references and the primitive arrays (triangles, spheres, planes), each
// as element count x element size (spare vector capacity, an accident of how an array was
// grown, is not counted). Not counted: what only shading reads (per-primitive materials
// and vertex normals).
std::size_t accel_bytes(const Accel& acc);

}  // namespace rt2
