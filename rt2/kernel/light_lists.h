// rt2/kernel/light_lists.h — the render kernel's lights stage: which lights each hit of a
// batch considers (RenderSettings::light_culling): all of them, one list per block (tiled)
// or per depth slice of a block (clustered) for primary hits, a walk of the light tree from
// each point for the others; with, per list, the lights its cluster provably sees whole
// (lights/cluster_visibility.h). Every mode gives the same image: the lights a list leaves
// out are those out of range, whose contribution is exactly 0.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "rt2/kernel/kernel.h"

#include "rt2/kernel/batches.h"
#include "rt2/render/renderer.h"

namespace rt2::RT2_ISA {

// The depth slice (0 ... slices - 1) of depth z in [near, far]: exponentially spaced when
// near > 0 (as clustered shading slices a frustum), evenly otherwise.
inline int depth_slice(float z, float near, float far, int slices) {
  if (!(far > near)) return 0;
  const float x = near > 0.0f ? std::log(z / near) / std::log(far / near) * float(slices)
                              : (z - near) / (far - near) * float(slices);
  return x >= float(slices - 1) ? slices - 1 : (x > 0.0f ? int(x) : 0);
}

// Whether hits get light lists: culling is on, some light has a range (without one, every
// light reaches everywhere), and at most kMaxListedUnbounded lights have none (every list
// repeats those: beyond, a list per point would cost more than testing every light).
inline constexpr std::size_t kMaxListedUnbounded = 1024;
inline bool uses_light_lists(const Renderer& r) {
  const LightBvh& lights = r.scene().light_bvh;
  return r.settings().light_culling != LightCulling::none && lights.has_bounded() &&
         lights.unbounded().size() <= kMaxListedUnbounded;
}

// The lights each hit of the batch considers (RenderSettings::light_culling), as
// lists in b.light_items.
inline void find_lights(const Renderer& r, bool primary, Batches& b, LightCounts& counts) {
  const CompiledScene& sc = r.scene();
  const RenderSettings& st = r.settings();
  const std::size_t n = b.rays.size();
  b.light_items.clear();
  b.list_begin.clear();
  b.list_begin.push_back(0);
  b.list_of.resize(n);
  b.list_sees.clear();
  // A list for the hits inside `cluster`: its lights, and which of them every hit there
  // provably sees (when shadow rays are traced at all).
  const auto add_cluster_list = [&](const Aabb& cluster) {
    b.list_sees.resize(b.list_sees.size() + b.found.size(), 0);
    if (st.shadows) {
      Aabb reach = cluster;
      for (const std::uint32_t li : b.found)
        if (sc.lights[li].has_range()) reach.grow(sc.lights[li].position);
      b.visibility.gather(sc.accel, cluster, reach);
      std::uint8_t* sees = b.list_sees.data() + b.light_items.size();
      for (std::size_t k = 0; k < b.found.size(); ++k) {
        const Light& l = sc.lights[b.found[k]];
        sees[k] = l.has_range() && b.visibility.sees(l.position);
      }
    }
  };
  const auto add_list = [&]() {
    if (b.list_sees.size() < b.light_items.size() + b.found.size())
      b.list_sees.resize(b.light_items.size() + b.found.size(), 0);
    b.light_items.insert(b.light_items.end(), b.found.begin(), b.found.end());
    b.list_begin.push_back(static_cast<std::uint32_t>(b.light_items.size()));
    ++counts.lists;
    counts.list_entries += b.found.size();
    return static_cast<std::uint32_t>(b.list_begin.size() - 2);
  };
  const auto fill = [&](const Aabb& box) {
    if (st.light_lists == LightLists::bvh)
      sc.light_bvh.lights_near(box, b.found);
    else
      sc.light_bvh.lights_near_brute_force(box, b.found);
  };
  if (primary && st.light_culling == LightCulling::tiled) {
    // One list for the block: the lights that reach its hits' bounds.
    Aabb box;
    for (std::size_t i = 0; i < n; ++i)
      if (b.hits[i].found()) box.grow(b.points[i].above);
    if (box.is_empty()) return;
    fill(box);
    add_cluster_list(box);
    const std::uint32_t list = add_list();
    std::fill(b.list_of.begin(), b.list_of.end(), list);
  } else if (primary && st.light_culling == LightCulling::clustered) {
    // A list per depth slice of the block: the lights that reach the bounds of the slice's
    // hits (the clusters the hits occupy: empty ones get none).
    const vec4& eye = r.camera().position();
    const vec4& forward = r.camera().forward();
    b.depth.resize(n);
    float near = kInfinity, far = -kInfinity;
    for (std::size_t i = 0; i < n; ++i) {
      if (!b.hits[i].found()) continue;
      b.depth[i] = dot(b.points[i].above - eye, forward);
      near = std::min(near, b.depth[i]);
      far = std::max(far, b.depth[i]);
    }
    const int slices = st.light_slices;
    b.cluster_bounds.assign(static_cast<std::size_t>(slices), Aabb());
    for (std::size_t i = 0; i < n; ++i) {
      if (!b.hits[i].found()) continue;
      const int k = depth_slice(b.depth[i], near, far, slices);
      b.list_of[i] = static_cast<std::uint32_t>(k);
      b.cluster_bounds[static_cast<std::size_t>(k)].grow(b.points[i].above);
    }
    std::uint32_t slice_list[256];
    for (int k = 0; k < slices; ++k) {
      if (b.cluster_bounds[static_cast<std::size_t>(k)].is_empty()) continue;
      fill(b.cluster_bounds[static_cast<std::size_t>(k)]);
      add_cluster_list(b.cluster_bounds[static_cast<std::size_t>(k)]);
      slice_list[k] = add_list();
    }
    for (std::size_t i = 0; i < n; ++i)
      if (b.hits[i].found()) b.list_of[i] = slice_list[b.list_of[i]];
  } else {
    // A walk of the light tree from each hit's point.
    for (std::size_t i = 0; i < n; ++i) {
      if (!b.hits[i].found()) continue;
      sc.light_bvh.lights_near(b.points[i].above, b.found);
      b.list_of[i] = add_list();
    }
  }
}

}  // namespace rt2::RT2_ISA
