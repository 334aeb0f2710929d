// rt2/image/image_io.cpp — image files through the codec (image_codec.h) and output_file.h.
#include "rt2/image/image_io.h"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>

#include "rt2/base/error.h"
#include "rt2/image/file_screen.h"
#include "rt2/image/image_codec.h"
#include "rt2/image/output_file.h"
#include "rt2/image/srgb.h"

namespace rt2 {

namespace {

std::string extension_of(const std::string& path) {
  return std::filesystem::path(path).extension().string();
}

}  // namespace

bool is_linear_format(const std::string& path) {
  std::string ext = extension_of(path);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".exr" || ext == ".hdr" || ext == ".tif" || ext == ".tiff";
}

void check_writable_image(const std::string& path) {
  io::check_output_path(path);
  const std::string ext = extension_of(path);
  if (ext.empty()) throw Error(path + ": output file needs an extension (.png, .exr, .ppm, ...)");
  const ImageCodec* codec = nullptr;
  try {
    codec = &image_codec();
  } catch (const Error& e) {
    throw Error(path + ": " + e.what());
  }
  const std::string why = codec->can_encode(ext);
  if (!why.empty()) throw Error(path + ": unsupported output format '" + ext + "' (" + why + ")");
}

void write_image(const std::string& path, const Image& image, const Display& display) {
  try {
    check_writable_image(path);
  } catch (const Error& e) {
    throw Error(std::string("cannot write ") + e.what());
  }
  const bool linear = is_linear_format(path);
  std::vector<float> encoded;
  if (!linear) {
    encoded = image.rgb;
    tonemap(encoded, display);
    for (float& v : encoded) v = srgb_encode(v);
  }
  std::string bytes;
  const std::string why =
      image_codec().encode(extension_of(path), linear ? image.rgb.data() : encoded.data(),
                           image.width, image.height, linear, linear ? "Linear" : "sRGB", bytes);
  if (!why.empty()) throw Error("cannot write " + path + ": " + why);
  io::write_output_file(path, bytes);
}

namespace {

// Why an image of header `h` may not be read, or "".
std::string header_problem(const ImageHeader& h, std::uint64_t max_pixels) {
  const auto size = [](std::int64_t w, std::int64_t ht) {
    return std::to_string(w) + " x " + std::to_string(ht) + " pixels";
  };
  if (h.deep) return "a deep image (several samples per pixel), which rt2 does not read";
  if (h.depth > 1) return "a volume of " + std::to_string(h.depth) + " slices, not a 2D image";
  if (h.width < 1 || h.height < 1) return "the image is empty (" + size(h.width, h.height) + ")";
  const auto limit = " is more than the limit of " + std::to_string(max_pixels) +
                     " (--max-texture-pixels raises it)";
  const std::uint64_t area = std::uint64_t(h.width) * std::uint64_t(h.height);
  if (area > max_pixels) return size(h.width, h.height) + limit;
  // The display window is what texture coordinates span and what OIIO makes mip levels of
  // (a 3 x 2 image in a display window of 7077891 x 16777217 overflowed its tile count).
  const std::uint64_t display = h.full_width > 0 && h.full_height > 0
                                    ? std::uint64_t(h.full_width) * std::uint64_t(h.full_height)
                                    : 0;
  if (display > max_pixels)
    return "its display window of " + size(h.full_width, h.full_height) + limit;
  if (std::max(area, display) > kMostImagePixels)
    return "more than 2^36 pixels, the most rt2 reads whatever the limit";
  if (h.channels < 1 || h.channels > kMaxImageChannels)
    return std::to_string(h.channels) + " channels (1 to " + std::to_string(kMaxImageChannels) +
           " are read)";
  if (h.subimages > kMaxSubimages)
    return "more than " + std::to_string(kMaxSubimages) + " subimages";
  if (h.miplevels > kMaxMipLevels)
    return "more than " + std::to_string(kMaxMipLevels) + " mip levels";
  constexpr std::int64_t kOrigin = std::int64_t(1) << 29, kSide = std::int64_t(1) << 30;
  const auto origin_ok = [&](std::int64_t v) { return v >= -kOrigin && v <= kOrigin; };
  const auto side_ok = [&](std::int64_t v) { return v >= 1 && v <= kSide; };
  if (!origin_ok(h.x) || !origin_ok(h.y) || !origin_ok(h.full_x) || !origin_ok(h.full_y) ||
      !side_ok(h.width) || !side_ok(h.height) || !side_ok(h.full_width) ||
      !side_ok(h.full_height))
    return "its data window (" + size(h.width, h.height) + " at " + std::to_string(h.x) + ", " +
           std::to_string(h.y) + ") or display window (" + size(h.full_width, h.full_height) +
           " at " + std::to_string(h.full_x) + ", " + std::to_string(h.full_y) +
           ") is beyond 2^29 pixels from the origin or 2^30 on a side";
  return "";
}

}  // namespace

ImageHeader read_image_header(const std::string& path, std::uint64_t max_pixels,
                              const std::string& name) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw Error(name + ": " + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) throw Error(name + ": is a directory");
  if (!S_ISREG(st.st_mode)) throw Error(name + ": not a regular file (a device or a pipe)");
  if (st.st_size == 0) throw Error(name + ": is empty");
  const std::string screened = screen_image_file(path, std::uint64_t(st.st_size));
  if (!screened.empty()) throw Error(name + ": " + screened);
  ImageHeader header;
  const std::string why = image_codec().probe(path, header);
  if (!why.empty()) throw Error(name + ": cannot read image: " + why);
  const std::string problem = header_problem(header, max_pixels);
  if (!problem.empty()) throw Error(name + ": " + problem);
  return header;
}

Image read_image(const std::string& path, std::uint64_t max_pixels) {
  const ImageHeader header = read_image_header(path, max_pixels, path);
  Image img;
  bool srgb = false;
  const std::string why = image_codec().decode(path, header, img.rgb, srgb);
  if (!why.empty()) throw Error(path + ": cannot read image: " + why);
  img.width = int(header.width);
  img.height = int(header.height);
  if (srgb)
    for (float& v : img.rgb) v = srgb_decode(v);
  return img;
}

}  // namespace rt2
