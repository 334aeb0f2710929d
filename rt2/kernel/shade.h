// rt2/kernel/shade.h — the render kernel's shading stage: every hit of a batch shaded by its
// material's model, its local light into its sample now, its lights' terms into the shadow
// batch and its secondary rays into the next batch; misses take the background.
//
// The material models are a closed set (scene/material.h, Shading), dispatched by one switch
// (shade_hit): a model is one file of this folder and one case there. Hits without texture
// or transparency are shaded 16, 8 or 4 at a time (phong_lanes.h, pbr_lanes.h), bit for
// bit as one by one.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>

#include "rt2/kernel/kernel.h"

#include "rt2/kernel/batches.h"
#include "rt2/kernel/environment_lanes.h"
#include "rt2/kernel/pbr.h"
#include "rt2/kernel/pbr_lanes.h"
#include "rt2/kernel/phong.h"
#include "rt2/kernel/phong_lanes.h"
#include "rt2/render/renderer.h"

namespace rt2::RT2_ISA {

// The surface point of every hit of the batch, into b.points.
inline void surface_points(const CompiledScene& sc, Batches& b) {
  const std::size_t n = b.rays.size();
  b.points.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    if (b.hits[i].found())
      b.points[i] = surface_at(sc.accel, b.rays.ray(i), b.hits[i], sc.offset_scale);
}


// One hit by its material's model. Forced inline at both call sites of shade_hits: a
// surface point built in one place and read through a pointer in another costs a
// store-forwarding stall per hit.
MLIB_INLINE void shade_hit(const CompiledScene& sc, const RenderSettings& st, int depth,
                           const PathRay& pr, const SurfacePoint& s, LightList lights,
                           float pixel_angle, Batches& b, RayCounts& counts) {
  switch (sc.materials[s.material].model) {
    case Shading::phong: return shade_phong(sc, st, depth, pr, s, lights, pixel_angle, b, counts);
    case Shading::pbr: return shade_pbr(sc, st, depth, pr, s, lights, pixel_angle, b, counts);
  }
}

// Each hit of the batch shaded with its lights and its secondary rays spawned; a miss takes
// the background. With lists, the surface points are b.points (surface_points made them,
// the lights stage used them); without, every hit considers every light and its surface
// point is made here (one pass over the hits).
// kHitLanes rays at a time: without lists and with at most kMaxLaneLights lights, the
// Phong or physically based hits among them are shaded in one SIMD pass (hit_lanes.h;
// RenderSettings::shading_lanes), the others one by one; each ray's results are then
// added in batch order, the same bits either way.
inline void shade_hits(const Renderer& r, bool lists, int depth, Batches& b, RayCounts& counts) {
  const CompiledScene& sc = r.scene();
  const RenderSettings& st = r.settings();
  // the angle a pixel spans at the image centre: a texture lookup's footprint per distance
  const float pixel_angle =
      2.0f * std::tan(r.camera().fov() * (std::numbers::pi_v<float> / 360.0f)) / float(st.height);
  const bool in_lanes = st.shading_lanes && !lists && sc.lights.size() <= kMaxLaneLights;
  HitLanes pass;  // every lane a pass reads, gather_lanes writes
  const std::uint32_t* samples = b.rays.columns().u(PathRays::kSample);
  const std::size_t n = b.rays.size();
  for (std::size_t first = 0; first < n; first += kHitLanes) {
    const std::size_t end = std::min(first + kHitLanes, n);
    unsigned shaded = 0;  // the lanes shaded in SIMD
    if (in_lanes) {
      // a pass shades the Phong hits in lanes, or, when it has none, the physically based
      // ones
      if (sc.any_plain_phong) shaded = gather_lanes(sc, sc.plain_phong.data(), b, first, end, pass);
      if (shaded) {
        shade_phong_lanes(sc, st, depth, shaded, b.rays, first, pass);
      } else if (sc.any_plain_pbr) {
        shaded = gather_lanes(sc, sc.plain_pbr.data(), b, first, end, pass);
        if (shaded) shade_pbr_lanes(sc, st, depth, shaded, b.rays, first, pass);
      }
      if (shaded) count_lanes(sc, pass, shaded, counts);
    }
    // When no other ray of the pass appends rays (they all missed), the lanes' rays are
    // appended a vector at a time (emit_lanes), with several lights only where no two rays
    // share a sample (primary rays; a scene whose hits never fork), else lane by lane.
    bool at_once =
        shaded != 0 && (sc.lights.size() <= 1 || depth == 0 || sc.one_ray_per_sample);
    for (std::size_t i = first; i < end && at_once; ++i)
      at_once = (shaded >> (i - first) & 1) || !b.hits[i].found();
    if (at_once) emit_lanes(sc, pass, samples + first, b);
    // The environment's radiance along the misses, in lanes where there are several.
    alignas(64) float sky[3][kHitLanes];
    bool sky_lanes = false;
    if (sc.has_environment && st.shading_lanes) {
      unsigned misses = 0;
      for (std::size_t i = first; i < end; ++i) misses |= unsigned(!b.hits[i].found()) << (i - first);
      if ((sky_lanes = std::popcount(misses) > 1)) {
        lanes::V dir[3], radiance[3];
        for (int c = 0; c < 3; ++c) dir[c] = lanes::V::loadu(b.rays.columns().f(PathRays::kDir + c) + first);
        alignas(64) float u[kHitLanes], v[kHitLanes];
        lanes::map_uv(sc.environment, dir, u, v);
        const EquirectMap* maps[kHitLanes];
        std::fill(maps, maps + kHitLanes, &sc.environment.source_map());
        lanes::bilinear(maps, u, v, misses, radiance);
        lanes::store3(radiance, sky);
      }
    }
    for (std::size_t i = first; i < end; ++i) {
      if (shaded >> (i - first) & 1) {
        const int l = int(i - first);
        if (at_once)
          b.colors[samples[i]] += pass.local(l);
        else
          emit_lane(sc, pass, l, samples[i], b);
        continue;
      }
      if (!b.hits[i].found()) {
        const int l = int(i - first);
        b.colors[samples[i]] +=
            b.rays.weight(i) *
            (!sc.has_environment ? sc.background
             : sky_lanes         ? vec4(sky[0][l], sky[1][l], sky[2][l])
                                 : sc.environment.radiance(b.rays.ray(i).dir));
        continue;
      }
      const PathRay pr = b.rays[i];
      if (lists) {
        const std::uint32_t k = b.list_of[i];
        shade_hit(sc, st, depth, pr, b.points[i],
                  LightList{b.light_items.data() + b.list_begin[k],
                            b.list_begin[k + 1] - b.list_begin[k], b.list_sees.data() + b.list_begin[k]},
                  pixel_angle, b, counts);
      } else {
        shade_hit(sc, st, depth, pr, surface_at(sc.accel, pr.ray, b.hits[i], sc.offset_scale),
                  LightList{nullptr, sc.lights.size()}, pixel_angle, b, counts);
      }
    }
  }
}

}  // namespace rt2::RT2_ISA
