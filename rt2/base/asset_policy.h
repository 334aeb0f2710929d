// rt2/base/asset_policy.h — what the files a user names may make rt2 read, and how large an
// image may be: the loaders (rt2/io/) and the image readers (textures, environments) apply
// it before they read or allocate. rt2cpr sets it from --allow-outside-assets and
// --max-texture-pixels.
#pragma once

#include <cstdint>

namespace rt2 {

struct AssetPolicy {
  // Whether a file an asset refers to (a glTF buffer or image, an OBJ's MTL library or an
  // MTL's texture) may lie outside the asset's own folder, after `..` and symbolic links.
  bool allow_outside_assets = false;
  // The most pixels a texture or environment image may have (width x height), checked from
  // its header before its pixels are read.
  std::uint64_t max_image_pixels = std::uint64_t(1) << 28;
};

}  // namespace rt2
