// rt2/render/renderer.h — the render core: the samples of one pass for one tile, into a film.
//
// A CompiledScene holds what rendering reads of the scene, built once and shared by every
// thread; a View holds the camera and the settings, chosen per frame; a Film holds the
// samples added so far. The Renderer binds a scene and a view to the kernel compiled for the
// scene's instruction set and triangle test (kernel_table.h). Each pixel's samples are split
// over `passes` passes in index order and every sample is computed on its own, so an image
// is the same bits whatever the tiles, passes, threads or scheduler (schedule.h).
#pragma once

#include <cstdint>
#include <vector>

#include "mlib/fpmode.h"
#include "rt2/image/film.h"
#include "rt2/render/compiled_scene.h"
#include "rt2/render/ray_counts.h"
#include "rt2/render/settings.h"
#include "rt2/render/supersampling.h"
#include "rt2/render/tile.h"

namespace rt2 {

class Renderer {
 public:
  // Keeps a reference to `scene`, which must outlive the Renderer. Validates the view's
  // settings (throws rt2::Error).
  Renderer(const CompiledScene& scene, const View& view);

  // The samples of pass `pass` (0 ... passes - 1) for the pixels of `tile`, added to `film`
  // (settings.width x settings.height), the rays counted into `counts`. Safe to call from
  // several threads at once for disjoint tiles. Runs with denormals flushed to zero (FTZ
  // and DAZ, mlib/fpmode.h), as Embree runs its kernels: an operation on a denormal can
  // cost ~100 cycles, and grazing rays and tiny triangles make them; the calling thread's
  // mode is restored afterwards.
  void render_tile(const Tile& tile, int pass, Film& film, RayCounts& counts) const {
    const bool was = mlib::set_flush_denormals(true);
    kernel_(*this, tile, samples_begin(pass), samples_begin(pass + 1), film, counts);
    mlib::set_flush_denormals(was);
  }

  // The first sample of pass p (p = passes gives the end).
  int samples_begin(int pass) const {
    return int(std::int64_t(settings().subpixels) * pass / settings().passes);
  }

  const CompiledScene& scene() const { return scene_; }
  // The camera of the next frames (an animated scene's next pose; the compiled scene it
  // refers to is updated in place, CompiledScene::place).
  void set_camera(const Camera& camera) { view_.camera = camera; }
  const Camera& camera() const { return view_.camera; }
  const RenderSettings& settings() const { return view_.settings; }
  const std::vector<SubpixelOffset>& offsets() const { return offsets_; }
  // The instruction set the kernel was compiled for.
  Isa isa() const { return scene_.accel.isa; }

  // A kernel: samples [s0, s1) of the tile's pixels (rt2/kernel/render_block.h).
  using Kernel = void (*)(const Renderer&, const Tile&, int s0, int s1, Film&, RayCounts&);

 private:
  const CompiledScene& scene_;
  View view_;
  std::vector<SubpixelOffset> offsets_;
  Kernel kernel_;
};

}  // namespace rt2
