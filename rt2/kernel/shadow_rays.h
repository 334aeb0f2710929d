// rt2/kernel/shadow_rays.h — a batch's shadow rays as columns (columns.h), each with the
// unshadowed term it adds to its sample, and the batch's shape (runs of one light) that lets
// the shadow stage trace it without sorting.
#pragma once

#include <cstdint>
#include <vector>

#include "rt2/kernel/kernel.h"

#include "rt2/kernel/path_rays.h"

namespace rt2::RT2_ISA {

// The shadow rays of a batch as columns (columns.h): each ray with the light's unshadowed
// term at the point it leaves (weight x (Kd (L·N) + Ks (R·V)^n) x light radiance), the
// distance to the light, its sample, its light (index into CompiledScene::lights) and
// whether it is proven to pass whole (cluster_visibility.h: then not traced).
//
// The batch keeps its shape as rays are added: whether its lights never decrease along it
// (one light, say: its runs are then its groups by light, and trace_shadows need not sort),
// the ends of its runs of one light, and whether some ray is proven unoccluded.
class ShadowRays {
 public:
  enum Column {
    kOrg = 0, kDir = 4, kTerm = 8, kDistance = 11, kSample = 12, kLight = 13, kUnoccluded = 14,
    kColumns = 15
  };
  static_assert(kOrg == 0 && kDir == 4);  // ray_in, ray_columns

  std::size_t size() const { return c_.size(); }
  bool empty() const { return c_.empty(); }
  void clear() {
    c_.clear();
    run_ends_.clear();
    grouped_ = true;
    some_unoccluded_ = false;
  }

  // Appends a shadow ray (the term's w is not kept).
  MLIB_INLINE void push(const vec4& org, const vec4& dir, float distance, const vec4& term,
                        std::uint32_t light, std::uint32_t sample, bool unoccluded) {
    const std::size_t i = extend(light, 1, unoccluded);
    for (int a = 0; a < 4; ++a) {
      c_.f(kOrg + a)[i] = org[a];
      c_.f(kDir + a)[i] = dir[a];
    }
    for (int k = 0; k < 3; ++k) c_.f(kTerm + k)[i] = term[k];
    c_.f(kDistance)[i] = distance;
    c_.u(kSample)[i] = sample;
    c_.u(kLight)[i] = light;
    c_.u(kUnoccluded)[i] = unoccluded;
  }
  // Adds n rays to `light` whose columns the caller fills (kLight and kUnoccluded
  // included); returns the index of the first.
  MLIB_INLINE std::size_t extend(std::uint32_t light, std::size_t n, bool unoccluded) {
    if (!c_.empty() && n > 0) {
      const std::uint32_t last = c_.u(kLight)[c_.size() - 1];
      grouped_ = grouped_ && last <= light;
      if (last != light) run_ends_.push_back(static_cast<std::uint32_t>(c_.size()));
    }
    some_unoccluded_ = some_unoccluded_ || (unoccluded && n > 0);
    return c_.extend(n);
  }

  MLIB_INLINE Ray ray(std::size_t i) const { return ray_in(c_, i); }
  MLIB_INLINE vec4 term(std::size_t i) const {
    return vec4(c_.f(kTerm)[i], c_.f(kTerm + 1)[i], c_.f(kTerm + 2)[i]);
  }
  float distance(std::size_t i) const { return c_.f(kDistance)[i]; }
  const float* distances() const { return c_.f(kDistance); }
  std::uint32_t sample(std::size_t i) const { return c_.u(kSample)[i]; }
  std::uint32_t light(std::size_t i) const { return c_.u(kLight)[i]; }
  bool unoccluded(std::size_t i) const { return c_.u(kUnoccluded)[i] != 0; }

  RayColumns rays() const { return ray_columns(c_); }
  Columns<kColumns>& columns() { return c_; }

  // The shape (see above).
  bool grouped() const { return grouped_; }
  bool some_unoccluded() const { return some_unoccluded_; }
  const std::vector<std::uint32_t>& run_ends() const { return run_ends_; }

 private:
  Columns<kColumns> c_;
  bool grouped_ = true, some_unoccluded_ = false;
  std::vector<std::uint32_t> run_ends_;
};

}  // namespace rt2::RT2_ISA
