// rt2/image_codec_oiio.cpp — the image codec on OpenImageIO, built as
// lib/librt2_image_codec.so (see image_codec.h). The only file of rt2 that includes OIIO.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>

#include "rt2/image_codec.h"

namespace {

using OIIO::ImageInput;
using OIIO::ImageOutput;
using OIIO::ImageSpec;
using OIIO::TypeDesc;

std::string one_line(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s.empty() ? "unknown error" : s;
}

// OIIO picks a format from a file name; only the extension matters.
std::string name_for(const std::string& extension) { return "image" + extension; }

std::string can_encode(const std::string& extension) {
  auto out = ImageOutput::create(name_for(extension));
  if (!out) return one_line(OIIO::geterror());
  if (!out->supports("ioproxy"))
    return "the " + std::string(out->format_name()) + " writer cannot write to memory";
  return "";
}

// "" when `bytes` decode as a width x height image of format `name`.
std::string verify(const std::string& name, std::vector<unsigned char>& bytes, int width,
                   int height) {
  OIIO::Filesystem::IOMemReader memory(bytes.data(), bytes.size());
  auto in = ImageInput::open(name, nullptr, &memory);
  if (!in) return one_line(OIIO::geterror());
  const ImageSpec& spec = in->spec();
  if (spec.width != width || spec.height != height) return "wrong size";
  std::vector<float> pixels(std::size_t(width) * std::size_t(height) * std::size_t(spec.nchannels));
  if (!in->read_image(0, 0, 0, spec.nchannels, TypeDesc::FLOAT, pixels.data()))
    return one_line(in->geterror());
  return "";
}

std::string encode(const std::string& extension, const float* rgb, int width, int height,
                   bool as_float, const std::string& color_space, std::string& bytes) {
  const std::string name = name_for(extension);
  auto out = ImageOutput::create(name);
  if (!out) return one_line(OIIO::geterror());
  std::vector<unsigned char> buffer;
  OIIO::Filesystem::IOVecOutput memory(buffer);
  if (!out->set_ioproxy(&memory)) return one_line(out->geterror());
  ImageSpec spec(width, height, 3, as_float ? TypeDesc::FLOAT : TypeDesc::UINT8);
  spec.attribute("oiio:ColorSpace", color_space);
  const bool ok = out->open(name, spec) && out->write_image(TypeDesc::FLOAT, rgb) && out->close();
  if (!ok) return one_line(out->geterror());
  // The error state alone cannot be trusted (OIIO 2.4's TIFF writer records a failed Exif
  // directory on every image it writes correctly): decode the bytes to prove them whole.
  const std::string why = verify(name, buffer, width, height);
  if (!why.empty()) return "the encoded image does not decode: " + why;
  bytes.assign(buffer.begin(), buffer.end());
  return "";
}

std::string decode(const std::string& path, std::vector<float>& rgb, int& width, int& height,
                   bool& srgb) {
  auto in = ImageInput::open(path);
  if (!in) return one_line(OIIO::geterror());
  const ImageSpec& spec = in->spec();
  if (spec.width < 1 || spec.height < 1 || spec.nchannels < 1 || spec.depth > 1)
    return "the image has no pixels, or is not a 2D image";
  const int nc = spec.nchannels;
  const std::size_t n = std::size_t(spec.width) * std::size_t(spec.height);
  std::vector<float> all(n * std::size_t(nc));
  if (!in->read_image(0, 0, 0, nc, TypeDesc::FLOAT, all.data())) return one_line(in->geterror());
  width = spec.width;
  height = spec.height;
  rgb.resize(n * 3);
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) rgb[3 * i + c] = all[i * nc + std::min(c, nc - 1)];
  const std::string cs = spec.get_string_attribute("oiio:ColorSpace");
  const bool integer = spec.format.basetype == TypeDesc::UINT8 ||
                       spec.format.basetype == TypeDesc::UINT16;
  srgb = integer && !OIIO::Strutil::iequals(cs, "linear");
  return "";
}

const rt2::ImageCodec kCodec{can_encode, encode, decode};

}  // namespace

extern "C" __attribute__((visibility("default"))) const rt2::ImageCodec* rt2_image_codec() {
  // One image is encoded or decoded at a time, after or before rendering: OIIO's and
  // OpenEXR's thread pools would only add threads that outlive the work (and that a leak
  // checker then finds half-started at exit).
  static const bool once = [] {
    OIIO::attribute("threads", 1);
    OIIO::attribute("exr_threads", 1);
    return true;
  }();
  (void)once;
  return &kCodec;
}
