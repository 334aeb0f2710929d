// rt2/render/renderer.h — the render core: one tile, for one pass of samples, into a film.
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
#include "rt2/scene/camera.h"
#include "rt2/render/compiled_scene.h"
#include "rt2/image/film.h"
#include "rt2/render/supersampling.h"
#include "rt2/render/tile.h"

namespace rt2 {

// Which lights a shading point considers (light_bvh.h). Every mode gives the same image:
// the lights a mode skips are those out of range, whose contribution is exactly 0.
enum class LightCulling {
  none,       // every light, tested one by one (brute force)
  tiled,      // primary hits: the lists of their block (a 2-D tile of the image)
  clustered,  // primary hits: the lists of their block's depth slice (a 3-D cluster)
  bvh,        // every hit: a walk of the light tree from its point
};
// How tiled and clustered culling fill a tile's or cluster's list.
enum class LightLists {
  brute_force,  // every light's sphere against the cluster's box (the papers' classic)
  bvh,          // a walk of the light tree with the cluster's box (the accelerated one)
};

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
  // BVH together where its rays allow (rt2/kernel/packet_traverse.h); false: every ray alone.
  // The image does not depend on it.
  bool packets = true;
  // Phong hits without texture or transparency are shaded kWidestLanes at a time in one
  // SIMD pass (rt2/kernel/phong_lanes.h) when every hit considers every light (no light lists)
  // and there are at most kMaxLaneLights (8) lights; false: one hit at a time. The image
  // does not depend on it.
  bool shading_lanes = true;
  // Lights: which ones each shading point considers (tiled and clustered culling use the
  // lists for primary hits and the light tree for the others), how the lists are filled,
  // and how many depth slices (1 ... 256) a block has for clustered culling: exponentially
  // spaced between its nearest and farthest primary hit, as clustered shading slices the
  // view frustum. None changes the image; clustered with the tree measured fastest
  // (scripts/sweep-many-lights).
  LightCulling light_culling = LightCulling::clustered;
  LightLists light_lists = LightLists::bvh;
  int light_slices = 16;
  // false: no shadow rays; every light reaches every point that faces it (for measuring
  // what shadows cost).
  bool shadows = true;
  // Time each stage of the kernel into RayCounts::stages (a clock read per stage and batch:
  // about 1.7 % of the headline frame, so off unless asked for).
  bool stage_times = false;

  // Throws rt2::Error for width/height < 1 or > 65535, subpixels < 1 or > 65536,
  // depth < 0 or > 1'000'000, min_weight NaN or outside [0, 1], passes < 1 or >
  // subpixels, block or light_slices < 1 or > 256.
  void validate() const;
};

// What a frame renders: where from, and how.
struct View {
  Camera camera;
  RenderSettings settings;
};

// Rays traced, by kind (primary rays are one per sample), with what the walks of the BVH
// cost for each kind (nodes and leaf blocks of four triangles visited), as pbrt reports.
// What the lights cost: shading points, the lights they considered (their lists: all of
// them without culling) and the lights in range among those; the light lists built for
// tiles and clusters, with their total length; and the shadow rays a cluster proved
// unoccluded (not traced, not counted in RayCounts::shadow).
struct LightCounts {
  std::uint64_t points = 0, considered = 0, in_range = 0, lists = 0, list_entries = 0;
  std::uint64_t unoccluded = 0;  // shadow rays proven to pass whole, not traced
  std::uint64_t in_lanes = 0;    // shading points shaded in SIMD lanes (phong_lanes.h)
  LightCounts& operator+=(const LightCounts& o) {
    points += o.points;
    considered += o.considered;
    in_range += o.in_range;
    unoccluded += o.unoccluded;
    lists += o.lists;
    list_entries += o.list_entries;
    in_lanes += o.in_lanes;
    return *this;
  }
};

// Nanoseconds spent in each stage of the kernel (tracer.h), summed over the threads, when
// RenderSettings::stage_times is on:
// generating primary rays, intersecting, finding each point's lights (lists and light-tree
// walks), shading (surface points, light terms, secondary rays, film), shadow rays.
struct StageTimes {
  std::uint64_t generate = 0, intersect = 0, lights = 0, shade = 0, shadow = 0;
  std::uint64_t total() const { return generate + intersect + lights + shade + shadow; }
  StageTimes& operator+=(const StageTimes& o) {
    generate += o.generate;
    intersect += o.intersect;
    lights += o.lights;
    shade += o.shade;
    shadow += o.shadow;
    return *this;
  }
};

struct RayCounts {
  std::uint64_t primary = 0, shadow = 0, reflection = 0, refraction = 0;
  TraversalCounts primary_walk, shadow_walk, secondary_walk;
  LightCounts lights;
  StageTimes stages;
  std::uint64_t total() const { return primary + shadow + reflection + refraction; }
  RayCounts& operator+=(const RayCounts& o) {
    primary += o.primary;
    shadow += o.shadow;
    reflection += o.reflection;
    refraction += o.refraction;
    primary_walk += o.primary_walk;
    shadow_walk += o.shadow_walk;
    secondary_walk += o.secondary_walk;
    lights += o.lights;
    stages += o.stages;
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
