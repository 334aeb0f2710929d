// rt2/image_io.h — writing (and reading) images through OpenImageIO.
//
// The format follows the file name's extension (at least .png, .exr, .ppm, also .jpg,
// .tif, .hdr ...). A write goes to a temporary file in the same folder, which is renamed
// over the target only when complete: a failed or interrupted write never leaves a
// half-written or empty file behind. This is the only file of rt2 that includes OIIO.
#pragma once

#include <string>

#include "rt2/image.h"

namespace rt2 {

// Checks, before any rendering, that `path` can be written: its extension names a format
// OIIO can write, and its folder exists and is writable. Throws rt2::Error naming the
// problem otherwise.
void check_writable_image(const std::string& path);

// Writes linear RGB floats. 8-bit formats (png, ppm, jpg) get values clamped to [0, 1]
// and rounded; float formats (exr, hdr) keep them. Throws rt2::Error (with OIIO's reason)
// on failure, leaving no file behind.
void write_image(const std::string& path, const Image& image);

// Reads any image OIIO can read as RGB floats (extra channels dropped, grey replicated).
Image read_image(const std::string& path);

}  // namespace rt2
