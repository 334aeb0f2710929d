// rt2/kernel/render_block.h — the render kernel: Whitted ray tracing (thesis 3.1, 3.2) of a
// tile, block by block (RenderSettings::block), breadth first through the ray tree: for a
// block and a range of samples, stages over batches of rays, each stage its own file.
//
// A ray's contribution is its weight (the product of the Kr / Kt or Fresnel factors along
// its path) times the light where it lands; a sample's terms are summed in the order the
// stages make them. Every sample is computed on its own, so the batches' sizes, the packets,
// the shading lanes and the instruction set never change a pixel.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>

#include "rt2/kernel/kernel.h"

#include "rt2/kernel/batches.h"
#include "rt2/kernel/generate.h"
#include "rt2/kernel/intersect.h"
#include "rt2/kernel/light_lists.h"
#include "rt2/kernel/shade.h"
#include "rt2/kernel/shadows.h"
#include "rt2/render/renderer.h"

namespace rt2::RT2_ISA {

// Each sample's colour added to the film, samples in index order.
inline void add_to_film(const Tile& block, int samples, const Batches& b, Film& film) {
  const vec4* colors = b.colors.data();
  for (int y = block.y0; y < block.y1; ++y)
    for (int x = block.x0; x < block.x1; ++x, colors += samples) film.add(x, y, colors, samples);
}

// Samples [s0, s1) of the pixels of `block` (at most RenderSettings::block squared) into the
// film, each stage's time added to counts.stages when RenderSettings::stage_times.
template <bool Watertight>
void render_block(const Renderer& r, const Tile& block, int s0, int s1, Film& film,
                  Batches& b, RayCounts& counts) {
  using Clock = std::chrono::steady_clock;
  const bool timed = r.settings().stage_times;
  Clock::time_point t = timed ? Clock::now() : Clock::time_point();
  const auto lap = [&t, timed](std::uint64_t& stage) {
    if (!timed) return;
    const Clock::time_point now = Clock::now();
    stage += static_cast<std::uint64_t>(
        std::chrono::duration_cast<std::chrono::nanoseconds>(now - t).count());
    t = now;
  };
  StageTimes& times = counts.stages;
  const CompiledScene& sc = r.scene();
  const RenderSettings& st = r.settings();
  const bool lists = uses_light_lists(r);
  const int samples = s1 - s0;
  const std::size_t n = std::size_t(block.x1 - block.x0) * std::size_t(block.y1 - block.y0) *
                        std::size_t(samples);
  b.colors.assign(n, vec4());
  film.prefetch(block.x0, block.y0, block.x1, block.y1, samples);  // for the film stage
  // 1. generate: one primary ray per sample
  generate(r, block, s0, s1, b);
  counts.primary += n;
  lap(times.generate);
  for (int depth = 0; !b.rays.empty(); ++depth) {
    const bool primary = depth == 0;
    b.next.clear();
    b.shadows.clear();
    // 2. intersect: the closest hit of every ray
    intersect<Watertight>(sc, st, primary, b, primary ? counts.primary_walk : counts.secondary_walk);
    lap(times.intersect);
    // 3. lights: the surface points and the lights each considers, with light lists
    if (lists) {
      surface_points(sc, b);
      lap(times.shade);
      find_lights(r, primary, b, counts.lights);
      lap(times.lights);
    }
    // 4. shade: local light into the samples, light terms into the shadow batch, secondary
    // rays into the next batch
    shade_hits(r, lists, depth, b, counts);
    lap(times.shade);
    // 5. shadows: what passes along each shadow ray, its term added to its sample
    trace_shadows<Watertight>(sc, st, b, counts.shadow_walk);
    add_shadow_terms(b);
    lap(times.shadow);
    // 6. next batch: the secondary rays, one level deeper
    std::swap(b.rays, b.next);
  }
  // 7. film
  add_to_film(block, samples, b, film);
  lap(times.film);
}

// Samples [s0, s1) of the pixels of `tile`, block by block, into the film.
template <bool Watertight>
void render_tile(const Renderer& r, const Tile& tile, int s0, int s1, Film& film,
                 RayCounts& counts) {
  static thread_local Batches batches;
  const int side = r.settings().block;
  RayCounts local;
  for (int y = tile.y0; y < tile.y1; y += side)
    for (int x = tile.x0; x < tile.x1; x += side) {
      const Tile block{x, y, std::min(x + side, tile.x1), std::min(y + side, tile.y1)};
      render_block<Watertight>(r, block, s0, s1, film, batches, local);
    }
  counts += local;
}

}  // namespace rt2::RT2_ISA
