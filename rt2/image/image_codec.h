// rt2/image/image_codec.h — encoding and decoding image files: the seam between rt2 and
// OpenImageIO, which rt2 loads only when an image is read or written.
//
// A plugin because libOpenImageIO pulls in hundreds of shared libraries (ffmpeg, gdal, …)
// whose loading and static initialisers cost time and address space before main, even for
// `rt2cpr --help`. The one file that includes OIIO, image_codec_oiio.cpp, is built as
// lib/librt2_image_codec.so beside bin/, and image_codec() dlopens it on first need. The
// codec works on bytes in memory (OIIO's IOProxy), never on the output file, so a full disk
// cannot abort it inside a format library (rt2/image/output_file.h writes the bytes).
// Functions return "" on success or a one-line reason; no exception crosses the library.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rt2 {

// What an image file's header declares (its first subimage's finest level), read without
// decoding a pixel: what rt2 checks before it reads one (image_io.h's read_image_header).
struct ImageHeader {
  std::string format;  // OIIO's name of the reader chosen for the file: "png", "openexr", ...
  std::int64_t width = 0, height = 0, depth = 0;  // the data window's size
  std::int64_t x = 0, y = 0;                      // and origin
  std::int64_t full_width = 0, full_height = 0;   // the display window's size
  std::int64_t full_x = 0, full_y = 0;            // and origin
  int channels = 0;
  bool deep = false;
  int subimages = 0;  // counted up to kMaxSubimages + 1
  int miplevels = 0;  // of the first subimage, counted up to kMaxMipLevels + 1
};
inline constexpr int kMaxSubimages = 64;
inline constexpr int kMaxMipLevels = 32;  // a chain from 2^31 texels down to 1

struct ImageCodec {
  // "" when files with this extension (".png") can be encoded, else why not.
  std::string (*can_encode)(const std::string& extension);
  // Encodes width x height RGB float pixels into the format of `extension`: as 32-bit
  // floats when `as_float`, else as 8-bit values (clamped to [0, 1], rounded), tagged with
  // the colour space `color_space` ("sRGB" or "Linear"); the file's bytes go to `bytes`.
  std::string (*encode)(const std::string& extension, const float* rgb, int width, int height,
                        bool as_float, const std::string& color_space, std::string& bytes);
  // Reads the header of the image file `path` (a regular file) into `header`, never a
  // pixel. Only the readers of PNG, JPEG, OpenEXR, Radiance HDR, TIFF, BMP, PNM and (by the
  // extension .tga alone) Targa files are used, chosen from the file's first bytes, not its
  // name: OIIO's other readers (camera raw, video, volumes, ...) are never reached.
  std::string (*probe)(const std::string& path, ImageHeader& header);
  // Decodes the image file `path`, whose header probe() read as `header` (the reader it
  // chose), into width x height RGB floats (extra channels dropped, the last of fewer than
  // three repeated) as stored; `srgb` says whether the values are sRGB-encoded (8- or
  // 16-bit files not tagged linear) rather than linear. Fails if the file no longer matches
  // `header`.
  std::string (*decode)(const std::string& path, const ImageHeader& header,
                        std::vector<float>& rgb, bool& srgb);

  // Textures through OIIO's TextureSystem (rt2/shading/texture.h): mip-mapped (in memory,
  // for files that have no mip levels), tiled and cached, filtered over a footprint.
  // OIIO's shared system (see image_codec_oiio.cpp for why); texture_system_destroy lets go
  // of it.
  void* (*texture_system_create)();
  void (*texture_system_destroy)(void* system);
  // A handle for the image file `path`, whose header probe() read as `header` (the reader
  // it chose), with every texel of every mip level read into the cache now, so that
  // lookups neither read nor make them; nullptr and `why` when that fails.
  void* (*texture_open)(void* system, const std::string& path, const ImageHeader& header,
                        std::string& why);
  // The filtered RGB at texture coordinates (s, t) (OIIO's: (0, 0) the top-left corner,
  // repeating), with the footprint's derivatives along the image's x and y; a grey image
  // (channels < 3) is replicated. Thread-safe.
  void (*texture_sample)(void* system, void* handle, int channels, float s, float t, float dsdx,
                         float dtdx, float dsdy, float dtdy, float* rgb);
  // The tiles the cache has made so far, read from files or mip-mapped: for tests that
  // check that lookups make none.
  long long (*texture_tiles_made)(void* system);
};

// The codec, loaded on the first call (thread-safe). Throws rt2::Error when the library
// cannot be loaded.
const ImageCodec& image_codec();

}  // namespace rt2

// The plugin's one exported symbol.
extern "C" const rt2::ImageCodec* rt2_image_codec();
