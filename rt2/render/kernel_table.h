// rt2/render/kernel_table.h — the renderer's entry into the kernel compiled for an
// instruction set (rt2/kernel/render_kernels.cpp defines one table per set). A Renderer looks
// its kernel up once; nothing dispatches per ray. Tests and benchmarks reach the kernel's
// queries through render/trace.h.
#pragma once

#include "rt2/base/isa.h"

namespace rt2 {

class Film;
class Renderer;
struct RayCounts;
struct Tile;

struct RenderKernels {
  // Samples [s0, s1) of a tile's pixels into a film (render/renderer.h).
  using RenderTile = void (*)(const Renderer&, const Tile&, int s0, int s1, Film&, RayCounts&);

  Isa isa;
  RenderTile render_tile[2];  // [0] the fast triangle test, [1] the watertight one
};

// The table of `isa`, which must be one of built_isas().
const RenderKernels& render_kernels(Isa isa);

}  // namespace rt2
