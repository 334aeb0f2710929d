// rt2/image_io.cpp — OpenImageIO output with write-to-temporary-then-rename.
#include "rt2/image_io.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "rt2/error.h"
#include "rt2/image_compare.h"

namespace rt2 {

namespace fs = std::filesystem;
using OIIO::ImageOutput;
using OIIO::ImageSpec;
using OIIO::TypeDesc;

namespace {

std::string one_line(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

fs::path folder_of(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? fs::path(".") : parent;
}

bool is_float_format(const std::string& ext) {
  return ext == ".exr" || ext == ".hdr" || ext == ".tif" || ext == ".tiff";
}

}  // namespace

void check_writable_image(const std::string& path) {
  const std::string ext = fs::path(path).extension().string();
  if (ext.empty()) throw Error(path + ": output file needs an extension (.png, .exr, .ppm, ...)");
  if (!ImageOutput::create(path))
    throw Error(path + ": unsupported output format '" + ext + "' (" + one_line(OIIO::geterror()) + ")");
  const fs::path dir = folder_of(path);
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw Error(path + ": output folder '" + dir.string() + "' does not exist");
  if (::access(dir.c_str(), W_OK) != 0)
    throw Error(path + ": output folder '" + dir.string() + "' is not writable");
  if (fs::is_directory(path, ec)) throw Error(path + ": is a directory");
}

void write_image(const std::string& path, const Image& image) {
  check_writable_image(path);
  const fs::path target(path);
  // Same folder (so rename is atomic), same extension (OIIO picks the format from it).
  const fs::path tmp = target.parent_path() /
                       ("." + target.stem().string() + ".tmp" + std::to_string(::getpid()) +
                        target.extension().string());
  auto out = ImageOutput::create(tmp.string());
  const std::string ext = target.extension().string();
  ImageSpec spec(image.width, image.height, 3, is_float_format(ext) ? TypeDesc::FLOAT : TypeDesc::UINT8);
  bool ok = out && out->open(tmp.string(), spec) &&
            out->write_image(TypeDesc::FLOAT, image.rgb.data()) && out->close();
  if (!ok) {
    const std::string why = out ? out->geterror() : OIIO::geterror();
    std::error_code ec;
    fs::remove(tmp, ec);
    throw Error(path + ": cannot write image: " + one_line(why));
  }
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw Error(path + ": cannot write image: " + ec.message());
  }
}

Image read_image(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw Error(path + ": cannot read image: " + one_line(OIIO::geterror()));
  const ImageSpec& spec = in->spec();
  if (spec.width < 1 || spec.height < 1 || spec.nchannels < 1)
    throw Error(path + ": image has no pixels");
  std::vector<float> all(std::size_t(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, TypeDesc::FLOAT, all.data()))
    throw Error(path + ": cannot read image: " + one_line(in->geterror()));
  Image img(spec.width, spec.height);
  const int nc = spec.nchannels;
  for (std::size_t i = 0; i < std::size_t(spec.width) * spec.height; ++i)
    for (int c = 0; c < 3; ++c) img.rgb[3 * i + c] = all[i * nc + std::min(c, nc - 1)];
  return img;
}

void rmse_psnr(const Image& a, const Image& b, double& rmse, double& psnr) {
  const ImageSpec spec(a.width, a.height, 3, TypeDesc::FLOAT);
  const OIIO::ImageBuf ba(spec, const_cast<float*>(a.rgb.data()));
  const OIIO::ImageBuf bb(spec, const_cast<float*>(b.rgb.data()));
  // Thresholds at infinity: only the statistics are wanted, no pixel "fails".
  const float never = std::numeric_limits<float>::infinity();
  const auto r = OIIO::ImageBufAlgo::compare(ba, bb, never, never);
  if (r.error) throw Error("image comparison failed: " + one_line(OIIO::geterror()));
  rmse = r.rms_error;
  // Peak 1.0 (OIIO's own PSNR takes the images' maximum value as the peak).
  psnr = rmse > 0.0 ? 20.0 * std::log10(1.0 / rmse) : std::numeric_limits<double>::infinity();
}

}  // namespace rt2
