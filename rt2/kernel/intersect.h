// rt2/kernel/intersect.h — the render kernel's intersection stage: the closest hit of every
// ray of a batch (closest_hit.h), the primary batch in its packets of 4 x 4 pixels, the
// others 16 rays at a time in batch order; one ray at a time when RenderSettings::packets
// is off, with the same answers.
#pragma once

#include <algorithm>

#include "rt2/kernel/kernel.h"

#include "rt2/kernel/batches.h"
#include "rt2/kernel/closest_hit.h"
#include "rt2/render/renderer.h"

namespace rt2::RT2_ISA {

// b.hits[i] = the closest hit of ray i for the rays [begin, end) of b.rays (at most
// kPacketSize), found as one packet or one ray at a time.
template <bool Watertight>
void intersect_packet(const CompiledScene& sc, const RenderSettings& st, std::size_t begin,
               std::size_t end, Batches& b, TraversalCounts& walk) {
  alignas(64) static constexpr float kNoBound[kPacketSize] = {kInfinity, kInfinity, kInfinity, kInfinity,
                                                  kInfinity, kInfinity, kInfinity, kInfinity,
                                                  kInfinity, kInfinity, kInfinity, kInfinity,
                                                  kInfinity, kInfinity, kInfinity, kInfinity};
  Hit* hits = b.hits.data() + begin;
  const int n = static_cast<int>(end - begin);
  if (st.packets) {
    closest_hit_packet<Watertight>(sc.accel, b.rays.rays(), begin, (PacketMask(1) << n) - 1, 0.0f,
                                   kNoBound, hits, &walk);
  } else {
    for (int l = 0; l < n; ++l)
      hits[l] = closest_hit<Watertight>(sc.accel, b.rays.ray(begin + std::size_t(l)), 0.0f,
                                        kInfinity, &walk);
  }
}


// b.hits: the closest hit of every ray of b.rays, the walks counted into `walk`.
template <bool Watertight>
void intersect(const CompiledScene& sc, const RenderSettings& st, bool primary, Batches& b,
               TraversalCounts& walk) {
  b.hits.resize(b.rays.size());
  if (primary) {
    for (std::size_t k = 0; k + 1 < b.packet_begin.size(); ++k)
      intersect_packet<Watertight>(sc, st, b.packet_begin[k], b.packet_begin[k + 1], b, walk);
  } else {
    for (std::size_t i = 0; i < b.rays.size(); i += kPacketSize)
      intersect_packet<Watertight>(sc, st, i, std::min(i + kPacketSize, b.rays.size()), b, walk);
  }
}

}  // namespace rt2::RT2_ISA
