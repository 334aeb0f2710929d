// rt2/shading/texture.h — the images materials sample: OpenImageIO's TextureSystem behind rt2's
// image codec library (rt2/image/image_codec.h), loaded only when a scene has textures.
//
// A TextureSet opens every TextureDesc of a scene when the scene is compiled: a missing,
// unreadable or too large image is one error line before rendering ("wood.png: ..."), not
// black pixels, and every texel is read and every mip level made then, not in the first
// frame. Embedded images (glTF buffers) are written to a private temporary folder first —
// OIIO's cache reads files — and removed with the set. Lookups are filtered by OIIO over a
// footprint (trilinear on the mip levels OIIO makes for files without their own,
// anisotropic where the footprint is) and repeat outside [0, 1].
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "rt2/base/asset_policy.h"
#include "rt2/geometry/ray.h"
#include "rt2/scene/scene.h"

namespace rt2 {

struct ImageCodec;

// Texture coordinates follow OBJ: (u, v) with image row 0 at v = 1. sRGB-encoded images
// (colours) are decoded to linear after filtering, the usual real-time shortcut (exact for
// a single texel; filtering encoded values darkens high-contrast edges slightly).
class TextureSet {
 public:
  TextureSet() = default;  // no textures
  // Opens every texture of `textures` (indices kept), each checked from its header first
  // (image_io.h's read_image_header: at most `max_pixels` pixels, ...). Throws rt2::Error
  // "PATH: reason" for the first that cannot be opened, removing what it made.
  explicit TextureSet(const std::vector<TextureDesc>& textures,
                      std::uint64_t max_pixels = AssetPolicy{}.max_image_pixels);
  ~TextureSet();
  TextureSet(TextureSet&& other) noexcept;
  TextureSet& operator=(TextureSet&& other) noexcept;
  TextureSet(const TextureSet&) = delete;
  TextureSet& operator=(const TextureSet&) = delete;

  std::size_t size() const { return handles_.size(); }

  // Texture `index`'s linear RGB at (u, v), filtered over a square footprint `width` wide in
  // texture coordinates (0: the finest level, bilinear). Thread-safe.
  vec4 sample(std::uint32_t index, float u, float v, float width) const;
  // The tiles OIIO's cache (which every set shares) has made so far, read from files or
  // mip-mapped; 0 without textures. For tests: sample() makes none.
  long long tiles_made() const;

 private:
  void release();

  const ImageCodec* codec_ = nullptr;
  void* system_ = nullptr;
  std::vector<void*> handles_;
  std::vector<int> channels_;
  std::vector<bool> srgb_;
  std::string temp_dir_;  // embedded images' files; empty when there are none
};

}  // namespace rt2
