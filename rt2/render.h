// rt2/render.h — the render core: one tile, for one pass of samples, into a film.
//
// Who owns what: a CompiledScene (compiled_scene.h) holds everything about the scene that
// rendering reads, built once and shared by every thread; a View holds where the camera is
// and how to render (size, samples, depth ...), chosen per frame; a Film (film.h) holds the
// samples added so far. The Renderer binds a scene and a view and picks the kernel compiled
// for the scene's instruction set (isa.h) and the triangle test (tracer.h).
//
// Its one entry point, render_tile, traces the samples of one pass for the pixels of one
// tile and adds them to the film. Each pixel's samples are split over `passes` passes in
// index order (pass p takes samples [N p / P, N (p + 1) / P)), and every sample is
// computed on its own, so an image is the same bits whatever the tiles, the passes, the
// threads or the scheduler (schedule.h hands tiles out).
#pragma once

#include <cstdint>
#include <vector>

#include "mlib/fpmode.h"
#include "rt2/bvh/wide_bvh.h"
#include "rt2/camera.h"
#include "rt2/compiled_scene.h"
#include "rt2/film.h"
#include "rt2/supersampling.h"

namespace rt2 {

struct RenderSettings {
  int width = 512;
  int height = 512;
  int subpixels = 1;              // samples per pixel, >= 1
  Pattern pattern = Pattern::grid;
  int depth = 1;                  // recursion depth: 0 = no reflection/refraction rays
  float min_weight = 0.01f;       // a secondary ray whose weight is <= this is not traced
  bool watertight = false;        // triangles: the watertight test instead of the fast one
  int passes = 1;                 // the samples of each pixel are rendered in this many
                                  // passes over the image, 1 ... subpixels
  // A tile is traced in square blocks of at most block x block pixels: a block's samples
  // are one batch of rays at each stage (primary, shadow, secondary), small enough to stay
  // in the caches. 1 ... 256; the image does not depend on it.
  int block = 16;
  // Primary rays are traced in packets of 4 x 4 pixels of one sample, shadow rays in
  // packets of 16 rays to one light, secondary rays 16 at a time, each packet walking the
  // BVH together where its rays allow (rt2/bvh/packet_traverse.h); false: every ray alone.
  // The image does not depend on it.
  bool packets = true;

  // Throws rt2::Error for width/height < 1 or > 65535, subpixels < 1 or > 65536,
  // depth < 0 or > 1'000'000, min_weight NaN or outside [0, 1], passes < 1 or >
  // subpixels, block < 1 or > 256.
  void validate() const;
};

// What a frame renders: where from, and how.
struct View {
  Camera camera;
  RenderSettings settings;
};

// A rectangle of pixels: columns [x0, x1), rows [y0, y1).
struct Tile {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

// Rays traced, by kind (primary rays are one per sample), with what the walks of the BVH
// cost for each kind (nodes and leaf blocks of four triangles visited), as pbrt reports.
struct RayCounts {
  std::uint64_t primary = 0, shadow = 0, reflection = 0, refraction = 0;
  TraversalCounts primary_walk, shadow_walk, secondary_walk;
  std::uint64_t total() const { return primary + shadow + reflection + refraction; }
  RayCounts& operator+=(const RayCounts& o) {
    primary += o.primary;
    shadow += o.shadow;
    reflection += o.reflection;
    refraction += o.refraction;
    primary_walk += o.primary_walk;
    shadow_walk += o.shadow_walk;
    secondary_walk += o.secondary_walk;
    return *this;
  }
};

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
  const Camera& camera() const { return view_.camera; }
  const RenderSettings& settings() const { return view_.settings; }
  const std::vector<SubpixelOffset>& offsets() const { return offsets_; }
  // The instruction set the kernel was compiled for.
  Isa isa() const { return scene_.accel.isa; }

  // A kernel: samples [s0, s1) of the tile's pixels (tracer.h).
  using Kernel = void (*)(const Renderer&, const Tile&, int s0, int s1, Film&, RayCounts&);

 private:
  const CompiledScene& scene_;
  View view_;
  std::vector<SubpixelOffset> offsets_;
  Kernel kernel_;
};

}  // namespace rt2
