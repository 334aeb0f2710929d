// rt2/image/image_io.cpp — image files through the codec (image_codec.h) and output_file.h.
#include "rt2/image/image_io.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "rt2/base/error.h"
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

Image read_image(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw Error(path + ": " + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) throw Error(path + ": is a directory");
  if (!S_ISREG(st.st_mode)) throw Error(path + ": not a regular file (a device or a pipe)");
  Image img;
  bool srgb = false;
  const std::string why = image_codec().decode(path, img.rgb, img.width, img.height, srgb);
  if (!why.empty()) throw Error(path + ": cannot read image: " + why);
  if (srgb)
    for (float& v : img.rgb) v = srgb_decode(v);
  return img;
}

}  // namespace rt2
