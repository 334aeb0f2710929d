// rt2/render/ray_counts.h — what a frame cost: rays by kind, BVH nodes and leaf blocks
// visited per kind (as pbrt reports), what the lights cost, and the time per kernel stage.
// Summed per thread and added up after the frame.
#pragma once

#include <cstdint>

#include "rt2/bvh/wide_bvh.h"

namespace rt2 {

// Rays traced, by kind (primary rays are one per sample), with what the walks of the BVH
// cost for each kind (nodes and leaf blocks of four triangles visited), as pbrt reports.
// What the lights cost: shading points, the lights they considered (their lists: all of
// them without culling) and the lights in range among those; the light lists built for
// tiles and clusters, with their total length; and the shadow rays a cluster proved
// unoccluded (not traced, not counted in RayCounts::shadow).
struct LightCounts {
  std::uint64_t points = 0, considered = 0, in_range = 0, lists = 0, list_entries = 0;
  std::uint64_t unoccluded = 0;  // shadow rays proven to pass whole, not traced
  std::uint64_t in_lanes = 0;    // shading points shaded in SIMD lanes (hit_lanes.h)
  std::uint64_t light_lanes = 0; // lights considered kLightLanes at a time (light_terms.h)
  LightCounts& operator+=(const LightCounts& o) {
    points += o.points;
    considered += o.considered;
    in_range += o.in_range;
    unoccluded += o.unoccluded;
    lists += o.lists;
    list_entries += o.list_entries;
    in_lanes += o.in_lanes;
    light_lanes += o.light_lanes;
    return *this;
  }
};

// Nanoseconds spent in each stage of the kernel (rt2/kernel/render_block.h), summed over the
// threads, when RenderSettings::stage_times is on: generating primary rays, intersecting,
// finding each point's lights (lists and light-tree walks), shading (surface points, light
// terms, secondary rays, the sky of misses), shadow rays, adding the samples to the film.
struct StageTimes {
  std::uint64_t generate = 0, intersect = 0, lights = 0, shade = 0, shadow = 0, film = 0;
  std::uint64_t total() const { return generate + intersect + lights + shade + shadow + film; }
  StageTimes& operator+=(const StageTimes& o) {
    generate += o.generate;
    intersect += o.intersect;
    lights += o.lights;
    shade += o.shade;
    shadow += o.shadow;
    film += o.film;
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

}  // namespace rt2
