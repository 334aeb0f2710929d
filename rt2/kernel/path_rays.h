// rt2/kernel/path_rays.h — the rays of the ray tree as a batch holds them: PathRay, one ray
// with its weight and sample, and PathRays, their columns (columns.h) that the packet
// queries and the shading lanes read and append to a vector at a time.
#pragma once

#include <cstdint>

#include "rt2/kernel/kernel.h"

#include "rt2/geometry/ray.h"
#include "rt2/kernel/columns.h"

namespace rt2::RT2_ISA {

// A batch whose first eight columns are its rays (origin x y z w, then direction x y z w):
// ray i, and the rays as RayColumns.
template <int C>
MLIB_INLINE Ray ray_in(const Columns<C>& c, std::size_t i) {
  return Ray(vec4(c.f(0)[i], c.f(1)[i], c.f(2)[i], c.f(3)[i]),
             vec4(c.f(4)[i], c.f(5)[i], c.f(6)[i], c.f(7)[i]));
}
template <int C>
RayColumns ray_columns(const Columns<C>& c) {
  return {{c.f(0), c.f(1), c.f(2), c.f(3)}, {c.f(4), c.f(5), c.f(6), c.f(7)}};
}

// A ray of the ray tree, and whose sample it adds to, as one-ray code reads it from a batch
// (PathRays). A ray's depth is its batch's, and its kind is counted when it is spawned.
struct PathRay {
  Ray ray;
  // The product of the reflection / transmission factors along the path, per channel: Kr
  // and Kt (the same in every channel) for Phong, Fresnel-weighted colours for physically
  // based surfaces (w = 0).
  vec4 w;
  std::uint32_t sample;  // index into the block's sample colours
  MLIB_INLINE const vec4& weight() const { return w; }
};

// The rays of a batch, PathRay's fields as columns (columns.h): operator[] gives one ray
// whole; the packet queries and the shading lanes read the columns.
class PathRays {
 public:
  enum Column { kOrg = 0, kDir = 4, kWeight = 8, kSample = 11, kColumns = 12 };  // x y z w / r g b
  static_assert(kOrg == 0 && kDir == 4);  // ray_in, ray_columns

  std::size_t size() const { return c_.size(); }
  bool empty() const { return c_.empty(); }
  void clear() { c_.clear(); }

  MLIB_INLINE PathRay operator[](std::size_t i) const { return PathRay{ray(i), weight(i), c_.u(kSample)[i]}; }
  MLIB_INLINE vec4 weight(std::size_t i) const {
    return vec4(c_.f(kWeight)[i], c_.f(kWeight + 1)[i], c_.f(kWeight + 2)[i]);
  }
  MLIB_INLINE Ray ray(std::size_t i) const { return ray_in(c_, i); }
  // Appends a ray (the weight's w is not kept).
  MLIB_INLINE void push(const vec4& org, const vec4& dir, const vec4& weight, std::uint32_t sample) {
    const std::size_t i = c_.extend(1);
    for (int a = 0; a < 4; ++a) {
      c_.f(kOrg + a)[i] = org[a];
      c_.f(kDir + a)[i] = dir[a];
    }
    for (int k = 0; k < 3; ++k) c_.f(kWeight + k)[i] = weight[k];
    c_.u(kSample)[i] = sample;
  }

  // Appends n <= 4 rays of weight 1 from `org` (a row of a packet of primary rays): their
  // directions dir[0 ... n - 1] and samples sample[0 ... n - 1], four lanes at a time.
  MLIB_INLINE void push_row(const vec4& org, const vec4 (&dir)[4], const std::uint32_t (&sample)[4],
                            int n) {
    namespace simd = mlib::simd;
    c_.reserve(c_.size() + 4);
    const std::size_t i = c_.size();
    simd::f4 x, y, z, w;
    simd::transpose4(org.m128(), org.m128(), org.m128(), org.m128(), x, y, z, w);
    simd::store(c_.f(kOrg) + i, x), simd::store(c_.f(kOrg + 1) + i, y);
    simd::store(c_.f(kOrg + 2) + i, z), simd::store(c_.f(kOrg + 3) + i, w);
    simd::transpose4(dir[0].m128(), dir[1].m128(), dir[2].m128(), dir[3].m128(), x, y, z, w);
    simd::store(c_.f(kDir) + i, x), simd::store(c_.f(kDir + 1) + i, y);
    simd::store(c_.f(kDir + 2) + i, z), simd::store(c_.f(kDir + 3) + i, w);
    for (int k = 0; k < 3; ++k) simd::store(c_.f(kWeight + k) + i, simd::set1(1.0f));
    for (int k = 0; k < 4; ++k) c_.u(kSample)[i + std::size_t(k)] = sample[k];
    c_.extend(std::size_t(n));
  }

  RayColumns rays() const { return ray_columns(c_); }
  Columns<kColumns>& columns() { return c_; }
  const Columns<kColumns>& columns() const { return c_; }

 private:
  Columns<kColumns> c_;
};

// Whether a ray of weight w is worth tracing: its largest channel exceeds `min_weight`.
MLIB_INLINE bool heavy_enough(const vec4& w, float min_weight) {
  return mlib::hmax3(w) > min_weight;
}

}  // namespace rt2::RT2_ISA
