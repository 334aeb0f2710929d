// rt2/image/file_screen.h — checks of an image file's bytes made before a format library
// reads it: sizes and counts that would make the library spend far more work or memory than
// the file's size justifies, found in files a few hundred bytes long (tests/hostile/images,
// tests/fuzz). read_image_header (image_io.h) runs them first.
#pragma once

#include <cstdint>
#include <string>

namespace rt2 {

// The most scans read_image_header lets a JPEG have (a progressive file needs about ten).
inline constexpr int kMaxJpegScans = 64;

// Why the regular file `path`, of `file_bytes` bytes, must not be given to its format
// library, or "" when it may:
// * a JPEG of more than kMaxJpegScans scans: libjpeg reads every scan over the whole image
//   when a progressive file is opened, so empty scans multiply that work;
// * an OpenEXR file whose header has an attribute longer than the file: OpenEXR allocates
//   an attribute's declared size before it reads it;
// * a run-length compressed BMP (RLE4, RLE8), which OIIO 2.4's reader decodes unsafely.
// Other files pass.
std::string screen_image_file(const std::string& path, std::uint64_t file_bytes);

}  // namespace rt2
