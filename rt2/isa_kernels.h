// rt2/isa_kernels.h — the entry points compiled once per instruction set (rt2/isa.h), as a
// table of function pointers: the render kernel, and batch ray queries for tests and
// benchmarks. A Renderer or a batch call looks its table up once; nothing dispatches per
// ray.
#pragma once

#include <cstddef>
#include <cstdint>

#include "rt2/isa.h"
#include "rt2/ray.h"

namespace rt2 {

struct Accel;
class Film;
class Renderer;
struct RayCounts;
struct Tile;
struct TraversalCounts;

struct IsaKernels {
  // Samples [s0, s1) of a tile's pixels into a film (rt2/render.h).
  using RenderTile = void (*)(const Renderer&, const Tile&, int s0, int s1, Film&, RayCounts&);
  // hits[i] = the closest hit of rays[i] in (0, t_max[i]) (rt2/query.h).
  using TraceClosest = void (*)(const Accel&, const Ray* rays, const float* t_max,
                                std::size_t n, Hit* hits, TraversalCounts* counts);
  // occluded[i] = 1 when anything lies on rays[i] in (0, t_max[i]), every surface opaque.
  using TraceOccluded = void (*)(const Accel&, const Ray* rays, const float* t_max,
                                 std::size_t n, std::uint8_t* occluded, TraversalCounts* counts);

  Isa isa;
  // Each indexed by the triangle test: [0] the fast one, [1] the watertight one.
  RenderTile render_tile[2];
  TraceClosest trace_closest[2];
  TraceOccluded trace_occluded[2];
};

// The table of `isa`, which must be one of built_isas().
const IsaKernels& isa_kernels(Isa isa);

}  // namespace rt2
