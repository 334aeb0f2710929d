// rt2/render.h — rendering rows of a frame.
//
// The Renderer is built once per frame setting: it validates the settings, notes the
// scene's features, precomputes the subpixel offsets and picks the kernel (rt2/tracer.h):
// the one compiled for the instruction set the Accel was built for (rt2/isa.h) and the
// chosen triangle test. `render_rows` is the whole per-pixel loop; it knows no scheduler
// (rt2/schedule.h splits a frame and calls it from any thread).
#pragma once

#include <cstdint>
#include <vector>

#include "mlib/fpmode.h"
#include "rt2/accel.h"
#include "rt2/image.h"
#include "rt2/scene.h"
#include "rt2/supersampling.h"

namespace rt2 {

struct RenderSettings {
  int width = 512;
  int height = 512;
  int subpixels = 1;              // samples per pixel, >= 1
  Pattern pattern = Pattern::grid;
  int depth = 1;                  // recursion depth: 0 = no reflection/refraction rays
  float min_weight = 0.01f;       // a secondary ray whose weight is <= this is not traced
  bool watertight = false;        // triangles: the watertight test instead of the fast one

  // Throws rt2::Error for width/height < 1 or > 65535, subpixels < 1 or > 65536,
  // depth < 0 or > 1'000'000, min_weight NaN or outside [0, 1].
  void validate() const;
};

// Rays traced, by kind (primary rays are one per subpixel), and a safety count: pixels
// whose colour came out NaN or infinite, which are written as 0 instead (never seen in a
// test render; reported by rt2cpr when it happens).
struct RayCounts {
  std::uint64_t primary = 0, shadow = 0, reflection = 0, refraction = 0;
  std::uint64_t nonfinite_pixels = 0;
  std::uint64_t total() const { return primary + shadow + reflection + refraction; }
  RayCounts& operator+=(const RayCounts& o) {
    primary += o.primary;
    shadow += o.shadow;
    reflection += o.reflection;
    refraction += o.refraction;
    nonfinite_pixels += o.nonfinite_pixels;
    return *this;
  }
};

class Renderer {
 public:
  // Keeps references to scene and accel: both must outlive the Renderer.
  Renderer(const Scene& scene, const Accel& accel, const RenderSettings& settings);

  // Renders rows [y0, y1) into `image` (which must be settings.width x settings.height)
  // and adds the rays traced to `counts`. Deterministic per pixel; safe to call from
  // several threads at once for disjoint rows.
  // Runs with denormals flushed to zero (FTZ and DAZ, mlib/fpmode.h), as Embree runs its
  // kernels: an operation on a denormal can cost ~100 cycles, and grazing rays and tiny
  // triangles make them. The calling thread's mode is restored afterwards.
  void render_rows(int y0, int y1, Image& image, RayCounts& counts) const {
    const bool was = mlib::set_flush_denormals(true);
    kernel_(*this, y0, y1, image, counts);
    mlib::set_flush_denormals(was);
  }

  const Scene& scene() const { return scene_; }
  const Accel& accel() const { return accel_; }
  const RenderSettings& settings() const { return settings_; }
  const std::vector<SubpixelOffset>& offsets() const { return offsets_; }
  // The features of the scene (reported; the kernel decides them per material).
  unsigned scene_features() const { return scene_features_; }
  // The scene's size, for offsetting secondary-ray origins (offset.h).
  float offset_scale() const { return offset_scale_; }
  // The instruction set the kernel was compiled for.
  Isa isa() const { return isa_; }

  using Kernel = void (*)(const Renderer&, int, int, Image&, RayCounts&);

 private:
  const Scene& scene_;
  const Accel& accel_;
  RenderSettings settings_;
  std::vector<SubpixelOffset> offsets_;
  unsigned scene_features_;
  Isa isa_;
  float offset_scale_;
  Kernel kernel_;
};

}  // namespace rt2
