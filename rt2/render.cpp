// rt2/render.cpp — settings validation and kernel selection.
#include "rt2/render.h"

#include <cmath>

#include "rt2/error.h"
#include "rt2/isa_kernels.h"

namespace rt2 {

void RenderSettings::validate() const {
  auto fail = [](const std::string& what) { throw Error(what); };
  if (width < 1 || width > 65535) fail("width must be in [1, 65535], got " + std::to_string(width));
  if (height < 1 || height > 65535)
    fail("height must be in [1, 65535], got " + std::to_string(height));
  if (subpixels < 1 || subpixels > 65536)
    fail("subpixels must be in [1, 65536], got " + std::to_string(subpixels));
  if (depth < 0 || depth > 1'000'000)
    fail("depth must be in [0, 1000000], got " + std::to_string(depth));
  if (!(min_weight >= 0.0f && min_weight <= 1.0f))
    fail("min-weight must be in [0, 1], got " + std::to_string(min_weight));
}

Renderer::Renderer(const Scene& scene, const Accel& accel, const RenderSettings& settings)
    : scene_(scene), accel_(accel), settings_(settings) {
  settings_.validate();
  offsets_ = subpixel_offsets(settings_.subpixels, settings_.pattern);
  scene_features_ = scene.features();
  offset_scale_ = scene.size();
  isa_ = accel.isa;
  kernel_ = isa_kernels(isa_).render_rows[settings_.watertight ? 1 : 0];
}

}  // namespace rt2
