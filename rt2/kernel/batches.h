// rt2/kernel/batches.h — the data one thread's render kernel passes from stage to stage
// (render_block.h), reused from block to block: the batch of rays, their hits and surface
// points, the light lists, the shadow rays and the sample colours.
#pragma once

#include <cstdint>
#include <vector>

#include "rt2/kernel/kernel.h"

#include "rt2/geometry/aabb.h"
#include "rt2/kernel/path_rays.h"
#include "rt2/kernel/shadow_rays.h"
#include "rt2/kernel/surface_point.h"
#include "rt2/lights/cluster_visibility.h"

namespace rt2::RT2_ISA {

// The lights a shading point considers: CompiledScene::lights[index[k]] for k < count, or
// every light (index null, count = all).
struct LightList {
  const std::uint32_t* index = nullptr;
  std::size_t count = 0;
  // Per light of the list, whether every shadow ray from the list's cluster to it provably
  // meets nothing (cluster_visibility.h); null: nothing proven.
  const std::uint8_t* sees = nullptr;
  std::uint32_t operator[](std::size_t k) const {
    return index ? index[k] : static_cast<std::uint32_t>(k);
  }
};

// A shadow ray's light and its index in the batch, for grouping the batch by light.
struct LightRay {
  std::uint32_t light, ray;
};

// The batches of one thread, reused from block to block (no allocation once grown).
struct Batches {
  PathRays rays, next;
  std::vector<std::uint32_t> packet_begin;  // the primary batch's packets (generate)
  std::vector<Hit> hits;                    // per ray of `rays`
  std::vector<SurfacePoint> points;         // per ray of `rays` that hit
  // Light lists: list k is light_items[list_begin[k], list_begin[k + 1]); the hit of ray
  // i uses list list_of[i]. No lists: every hit considers every light.
  std::vector<std::uint32_t> light_items, list_begin, list_of;
  std::vector<std::uint8_t> list_sees;  // parallel to light_items (see LightList::sees)
  ClusterVisibility visibility;
  std::vector<std::uint32_t> to_trace;  // the shadow rays to trace
  std::vector<std::uint32_t> found;     // one query's answer
  std::vector<float> depth;             // clustered culling: per ray, its hit's depth
  std::vector<Aabb> cluster_bounds;     // clustered culling: per slice
  ShadowRays shadows;
  std::vector<float> passed;              // per shadow ray: the light that passes
  std::vector<std::uint32_t> by_light;    // shadow rays grouped by light, in batch order
  std::vector<std::uint32_t> light_begin;
  std::vector<LightRay> light_rays;
  std::vector<vec4> colors;
};

}  // namespace rt2::RT2_ISA
