// rt2/kernel/transmittance.h — how much light passes along a shadow ray: 1 when nothing is in
// the way, 0 behind an opaque surface, else the product of the transparencies Kt of every
// surface crossed (each crossing counts once: a glass sphere crossed through attenuates
// twice, as a closed glass mesh does), over any_hit.h's crossings, for one ray and a packet.
#pragma once

#include <bit>
#include <cstdint>
#include <utility>
#include <vector>

#include "rt2/kernel/kernel.h"

#include "rt2/bvh/accel.h"
#include "rt2/kernel/any_hit.h"
#include "rt2/scene/material.h"

namespace rt2::RT2_ISA {

// The transparencies Kt of the surfaces a shadow ray crosses, multiplied in an order that
// does not depend on the order they are found in, so that every ISA, BVH width and walk
// (one ray or a packet) gives the same value: each distinct Kt is kept with how many times
// it was crossed, and the product runs over the values in ascending order, each as many
// times as it was crossed (for up to 16 crossings, the product of the sorted factors).
class Crossings {
 public:
  // Adds a crossing of a surface of transparency k; returns true when no light can pass
  // any more (k = 0: opaque).
  bool cross(float k) {
    if (k == 0.0f) return true;
    for (int i = 0; i < distinct_; ++i)
      if (values_[i] == k) {
        ++counts_[i];
        return false;
      }
    if (distinct_ < kDistinct) {
      values_[distinct_] = k;
      counts_[distinct_++] = 1;
    } else {
      overflow_ *= k;
    }
    return false;
  }
  // The product of the factors (when cross never returned true).
  float transmittance() {
    for (int i = 1; i < distinct_; ++i)  // ascending (insertion sort: few values)
      for (int j = i; j > 0 && values_[j] < values_[j - 1]; --j) {
        std::swap(values_[j], values_[j - 1]);
        std::swap(counts_[j], counts_[j - 1]);
      }
    float tr = 1.0f;
    for (int i = 0; i < distinct_; ++i)
      for (std::uint32_t n = 0; n < counts_[i]; ++n) tr *= values_[i];
    return tr * overflow_;
  }

 private:
  static constexpr int kDistinct = 16;
  float values_[kDistinct];
  std::uint32_t counts_[kDistinct];
  int distinct_ = 0;
  // Beyond 16 distinct transparencies on one ray (materials of 17 different Kt crossed):
  // in found order, the one case where the walk's order shows in the last bits.
  float overflow_ = 1.0f;
};

// The transmittance of the segment (t_min, t_max) of `ray`.
template <bool Watertight>
inline float transmittance(const Accel& acc, const std::vector<Material>& materials,
                           const Ray& ray, float t_min, float t_max,
                           TraversalCounts* counts = nullptr) {
  Crossings c;
  const auto cross = [&](PrimRef prim, std::uint32_t instance = kNoInstance) {
    return c.cross(materials[acc.material_of(prim, instance)].transparency);
  };
  return any_hit<Watertight>(acc, ray, t_min, t_max, cross, counts) ? 0.0f : c.transmittance();
}

// transmittance for each ray of a packet loaded into pr: passed[l] for the lanes l of
// `lanes` (`finite`: load_finite's answer), bit for bit what transmittance gives. t_max
// holds kPacketSize floats (all read, those outside `lanes` unused).
template <bool Watertight>
inline void transmittance_loaded(const Accel& acc, const std::vector<Material>& materials,
                                 PacketRays<kWidth>& pr, PacketMask lanes, PacketMask finite,
                                 float t_min, const float* t_max, float* passed,
                                 TraversalCounts* counts) {
  Crossings c[kPacketSize];
  for (PacketMask m = lanes & ~finite; m; m &= m - 1) passed[std::countr_zero(m)] = 1.0f;
  const auto cross = [&](int l, PrimRef prim, std::uint32_t instance = kNoInstance) {
    return c[l].cross(materials[acc.material_of(prim, instance)].transparency);
  };
  const PacketMask blocked =
      any_hit_loaded<Watertight>(acc, pr, finite, t_min, t_max, cross, counts);
  for (PacketMask m = finite; m; m &= m - 1) {
    const int l = std::countr_zero(m);
    passed[l] = blocked >> l & 1 ? 0.0f : c[l].transmittance();
  }
}

// transmittance_loaded for rays[l], l in `lanes`.
template <bool Watertight>
inline void transmittance_packet(const Accel& acc, const std::vector<Material>& materials,
                                 const Ray* rays, PacketMask lanes, float t_min,
                                 const float* t_max, float* passed,
                                 TraversalCounts* counts = nullptr) {
  LoadedPacket p(rays, lanes, t_max);
  transmittance_loaded<Watertight>(acc, materials, p.rays, lanes, p.finite, t_min, p.bound, passed,
                                   counts);
}

// transmittance_loaded for the rays first + l of columns, l in `lanes` (the columns are read
// at first ... first + kPacketSize - 1, and t_max's kPacketSize floats).
template <bool Watertight>
inline void transmittance_packet(const Accel& acc, const std::vector<Material>& materials,
                                 const RayColumns& rays, std::size_t first, PacketMask lanes,
                                 float t_min, const float* t_max, float* passed,
                                 TraversalCounts* counts = nullptr) {
  PacketRays<kWidth> pr;
  const PacketMask finite = load_finite(
      pr, lanes, [&rays, first](PacketRays<kWidth>& p, PacketMask m) { return p.load(rays, first, m); });
  transmittance_loaded<Watertight>(acc, materials, pr, lanes, finite, t_min, t_max, passed, counts);
}

}  // namespace rt2::RT2_ISA
