// rt2/kernel/shadows.h — the render kernel's shadow stage: the batch's shadow rays traced
// (transmittance.h), grouped by light into packets, and each ray's term times the light that
// passes added to its sample in batch order. A ray from a cluster to a light it provably
// sees whole (lights/cluster_visibility.h) is not traced: it passes 1, as its walk would
// return.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "rt2/kernel/kernel.h"

#include "rt2/kernel/batches.h"
#include "rt2/kernel/transmittance.h"
#include "rt2/render/renderer.h"

namespace rt2::RT2_ISA {

// With packets, the rays of each light are traced together (rays to one light from
// neighbouring points are coherent), 16 at a time in batch order; a light with fewer than
// kMinShadowPacket rays (many small lights, each reaching a few points) has them traced one
// by one.
inline constexpr std::size_t kMinShadowPacket = 4;

// b.by_light: the rays of b.to_trace grouped by light, stable; b.light_begin: the ends of
// the groups. A counting sort over the lights when there are fewer lights than rays, else
// a sort of the rays (whose cost does not grow with the scene's light count).
inline void group_by_light(const CompiledScene& sc, Batches& b) {
  const std::size_t m = b.to_trace.size();
  b.by_light.resize(m);
  b.light_begin.clear();
  const auto light_of = [&b](std::size_t k) { return b.shadows.light(b.to_trace[k]); };
  if (sc.lights.size() <= m) {
    b.light_begin.resize(sc.lights.size() + 1);  // zeros
    for (const std::uint32_t i : b.to_trace) ++b.light_begin[b.shadows.light(i) + 1];
    for (std::size_t l = 1; l < b.light_begin.size(); ++l)
      b.light_begin[l] += b.light_begin[l - 1];
    for (const std::uint32_t i : b.to_trace) b.by_light[b.light_begin[b.shadows.light(i)]++] = i;
    // light_begin[l] is now the end of light l's run.
  } else {
    // Sorted by (light, ray): stable by construction. (A sort of a type of this namespace:
    // std::sort of plain integers would be instantiated here and in the portable code
    // alike, and the linker could keep this instruction set's copy for both.)
    b.light_rays.resize(m);
    for (std::size_t k = 0; k < m; ++k) b.light_rays[k] = {light_of(k), b.to_trace[k]};
    std::sort(b.light_rays.begin(), b.light_rays.end(), [](const LightRay& x, const LightRay& y) {
      return x.light < y.light || (x.light == y.light && x.ray < y.ray);
    });
    for (std::size_t k = 0; k < m; ++k) b.by_light[k] = b.light_rays[k].ray;
    for (std::size_t k = 1; k <= m; ++k)
      if (k == m || b.light_rays[k].light != b.light_rays[k - 1].light)
        b.light_begin.push_back(static_cast<std::uint32_t>(k));
  }
}

// b.passed[i] = the light that passes along shadow ray i.
template <bool Watertight>
void trace_shadows(const CompiledScene& sc, const RenderSettings& st, Batches& b,
                   TraversalCounts& walk) {
  const std::size_t n = b.shadows.size();
  b.passed.resize(n);
  if (!st.shadows) {
    std::fill(b.passed.begin(), b.passed.end(), 1.0f);
    return;
  }
  const auto one = [&](std::uint32_t i) {
    b.passed[i] = transmittance<Watertight>(sc.accel, sc.materials, b.shadows.ray(i), 0.0f,
                                            b.shadows.distance(i), &walk);
  };
  // Rays proven unoccluded pass whole (what their walk would return); the others are traced
  // (b.to_trace), with packets in groups by light (b.by_light, ending at b.light_begin).
  // A batch with no proven ray whose lights never decrease (one light, say) is its own
  // grouping: its runs, which ShadowRays kept as they were added.
  const bool as_is = b.shadows.grouped() && !b.shadows.some_unoccluded();
  if (as_is) {
    if (!st.packets) {
      for (std::size_t i = 0; i < n; ++i) one(static_cast<std::uint32_t>(i));
      return;
    }
  } else {
    b.to_trace.clear();
    for (std::size_t i = 0; i < n; ++i) {
      if (b.shadows.unoccluded(i))
        b.passed[i] = 1.0f;
      else
        b.to_trace.push_back(static_cast<std::uint32_t>(i));
    }
    if (!st.packets) {
      for (const std::uint32_t i : b.to_trace) one(i);
      return;
    }
    group_by_light(sc, b);
  }
  // Packets of up to 16 rays of a run; in a batch traced as it is, a packet's rays are
  // consecutive and load straight from the columns.
  const auto trace_run = [&](std::size_t run, std::size_t run_end) {
    if (run_end - run < kMinShadowPacket) {
      for (; run < run_end; ++run) one(as_is ? static_cast<std::uint32_t>(run) : b.by_light[run]);
      return;
    }
    for (; run < run_end; run += kPacketSize) {
      const int count = static_cast<int>(std::min<std::size_t>(kPacketSize, run_end - run));
      const PacketMask lanes = (PacketMask(1) << count) - 1;
      if (as_is) {
        transmittance_packet<Watertight>(sc.accel, sc.materials, b.shadows.rays(), run, lanes, 0.0f,
                                         b.shadows.distances() + run, b.passed.data() + run, &walk);
        continue;
      }
      Ray rays[kPacketSize];
      float t_max[kPacketSize], passed[kPacketSize];
      for (int l = 0; l < count; ++l) {
        rays[l] = b.shadows.ray(b.by_light[run + l]);
        t_max[l] = b.shadows.distance(b.by_light[run + l]);
      }
      transmittance_packet<Watertight>(sc.accel, sc.materials, rays, lanes, 0.0f, t_max, passed,
                                       &walk);
      for (int l = 0; l < count; ++l) b.passed[b.by_light[run + l]] = passed[l];
    }
  };
  // The runs: of the batch as it is (ShadowRays kept their ends), or of its groups.
  const std::vector<std::uint32_t>& ends = as_is ? b.shadows.run_ends() : b.light_begin;
  std::size_t run = 0;
  for (const std::uint32_t run_end : ends) {
    trace_run(run, run_end);
    run = run_end;
  }
  if (as_is) trace_run(run, n);
}


// Each shadow ray's term times what passed, added to its sample, in batch order.
inline void add_shadow_terms(Batches& b) {
  for (std::size_t i = 0; i < b.shadows.size(); ++i)
    if (b.passed[i] != 0.0f) b.colors[b.shadows.sample(i)] += b.shadows.term(i) * b.passed[i];
}

}  // namespace rt2::RT2_ISA
