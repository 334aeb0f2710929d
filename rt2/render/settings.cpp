// rt2/render/settings.cpp — the settings' ranges.
#include "rt2/render/settings.h"

#include <string>

#include "rt2/base/error.h"

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
  if (passes < 1 || passes > subpixels)
    fail("passes must be in [1, subpixels = " + std::to_string(subpixels) + "], got " +
         std::to_string(passes));
  if (block < 1 || block > 256) fail("block must be in [1, 256], got " + std::to_string(block));
  if (light_slices < 1 || light_slices > 256)
    fail("light slices must be in [1, 256], got " + std::to_string(light_slices));
}

}  // namespace rt2
