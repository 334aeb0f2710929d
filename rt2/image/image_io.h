// rt2/image/image_io.h — image files: writing rendered frames and reading reference images.
//
// The format follows the file name's extension (.png, .exr, .ppm, .jpg, .tif, .hdr, and
// whatever else the codec can write to memory). Float formats (.exr, .hdr, .tif) store the
// renderer's linear RGB values as they are. Display formats (.png, .jpg, .ppm and every
// other 8-bit format) store values mapped by a Display (tonemap.h; the default leaves them
// as they are), sRGB-encoded (srgb.h), clamped to [0, 1], rounded to 8 bits and tagged sRGB.
// Reading undoes the encoding, so a reference image is compared in linear values. Images
// are encoded in memory (image_codec.h, OpenImageIO loaded on first use) and written by
// output_file.h: the file appears complete or not at all.
#pragma once

#include <cstdint>
#include <string>

#include "rt2/image/image.h"
#include "rt2/image/image_codec.h"
#include "rt2/image/tonemap.h"

namespace rt2 {

// Checks, before any rendering, that `path` can be written: the target is acceptable to
// rt2::io::check_output_path, and its extension names a format the codec can write.
// Throws rt2::Error naming the problem otherwise.
void check_writable_image(const std::string& path);

// True for the formats that store linear float values (.exr, .hdr, .tif, .tiff).
bool is_linear_format(const std::string& path);

// Writes the linear RGB `image` as above. Throws rt2::Error "cannot write PATH: reason" on
// any failure, leaving no file (and no temporary file) behind.
// Display formats take `display`'s exposure and curve first; float formats ignore it.
void write_image(const std::string& path, const Image& image, const Display& display = {});

// The most channels an image rt2 reads may have, and the most pixels in either of its
// windows whatever the pixel limit.
inline constexpr int kMaxImageChannels = 64;
inline constexpr std::uint64_t kMostImagePixels = std::uint64_t(1) << 36;
// read_image's default: no limit on an image's pixels.
inline constexpr std::uint64_t kNoPixelLimit = UINT64_MAX;

// What the image file `path` declares, read and checked from its header alone: no pixel is
// decoded and nothing of the image's size is allocated. Throws rt2::Error "NAME: reason",
// NAME being how the user knows the file (its path, or "x.glb:image 2"), unless it is a
// regular file (not a directory, device or pipe, which may never end), not empty, passes
// file_screen.h's checks, is in a format image_codec.h's probe reads, flat (not deep) and
// 2D, with 1 to kMaxImageChannels channels, at most kMaxSubimages subimages and
// kMaxMipLevels levels, windows within 2^29 pixels of the origin and at most 2^30 on a
// side, and at most `max_pixels` (and kMostImagePixels) pixels in its data window (the
// pixels stored) and in its display window:
//   big.png: 20000 x 20000 pixels is more than the limit of 268435456 (--max-texture-pixels raises it)
ImageHeader read_image_header(const std::string& path, std::uint64_t max_pixels,
                              const std::string& name);

// Reads the image file `path`, checked as read_image_header does, as linear RGB floats.
// Throws rt2::Error "PATH: reason" when it cannot.
Image read_image(const std::string& path, std::uint64_t max_pixels = kNoPixelLimit);

}  // namespace rt2
