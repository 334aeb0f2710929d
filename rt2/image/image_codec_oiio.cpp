// rt2/image/image_codec_oiio.cpp — the image codec on OpenImageIO, built as
// lib/librt2_image_codec.so (see image_codec.h). The only file of rt2 that includes OIIO.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/texture.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <vector>

#include "rt2/image/image_codec.h"

namespace {

using OIIO::ImageInput;
using OIIO::ImageOutput;
using OIIO::ImageSpec;
using OIIO::TypeDesc;

// OIIO's messages on one line, and short: a broken file can make it repeat the same
// complaint for every tile it tried.
std::string one_line(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  while (!s.empty() && s.back() == ' ') s.pop_back();
  if (s.size() > 200) s = s.substr(0, 200) + " ...";
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

std::string decode_loudly(const std::string& path, std::vector<float>& rgb, int& width,
                          int& height, bool& srgb) {
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

// Runs `f` with the process's stderr pointed at /dev/null: libpng and libjpeg print their
// own complaints there before OIIO reports the error rt2 turns into its one line. Only for
// what runs before or after rendering, on one thread (file descriptors are per process).
template <typename F>
auto quietly(F&& f) {
  std::fflush(stderr);
  const int saved = ::dup(2);
  const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
  if (saved >= 0 && null >= 0) ::dup2(null, 2);
  if (null >= 0) ::close(null);
  struct Restore {
    int saved;
    ~Restore() {
      std::fflush(stderr);
      if (saved >= 0) {
        ::dup2(saved, 2);
        ::close(saved);
      }
    }
  } restore{saved};
  return f();
}

std::string decode(const std::string& path, std::vector<float>& rgb, int& width, int& height,
                   bool& srgb) {
  return quietly([&] { return decode_loudly(path, rgb, width, height, srgb); });
}

OIIO::TextureSystem* system_of(void* s) { return static_cast<OIIO::TextureSystem*>(s); }

// OIIO's shared TextureSystem, set up once. Not one of its own per TextureSet: OIIO 2.4's
// TextureSystem::destroy frees a private system through the wrong type (AddressSanitizer:
// new-delete-type-mismatch), and the shared one is never freed before exit. Its cache holds
// at most max_memory_MB whatever the number of scenes a process compiles.
void* texture_system_create() {
  static OIIO::TextureSystem* const ts = [] {
    OIIO::TextureSystem* t = OIIO::TextureSystem::create(/*shared=*/true);
    t->attribute("automip", 1);    // mip levels for plain PNG/JPEG files, made in memory
    t->attribute("autotile", 64);  // and tiles, so a large image is read in pieces
    t->attribute("max_memory_MB", 1024.0f);
    return t;
  }();
  return ts;
}

// A TextureSet's files stay in the shared cache until a later texture_open of the same name
// invalidates them.
void texture_system_destroy(void*) {}

void* texture_open(void* s, const std::string& path, int& channels, std::string& why) {
  OIIO::TextureSystem* ts = system_of(s);
  return quietly([&]() -> void* {
    // a file of this name read before (by an earlier scene) may have changed since
    ts->invalidate(OIIO::ustring(path), /*force=*/true);
    OIIO::TextureSystem::TextureHandle* h = ts->get_texture_handle(OIIO::ustring(path));
    ImageSpec spec;
    if (!h || !ts->get_imagespec(h, nullptr, 0, spec)) {
      why = one_line(ts->geterror());
      return nullptr;
    }
    if (spec.width < 1 || spec.height < 1 || spec.nchannels < 1) {
      why = "the image has no pixels";
      return nullptr;
    }
    // Read every texel of the finest level now, a strip of rows at a time, so that a file
    // truncated or corrupt past its header is an error here and not black texels (and a
    // complaint per tile) while rendering; the cache keeps what it read.
    OIIO::TextureOpt opt;
    const int rows = std::max(1, (1 << 22) / std::max(1, spec.width * spec.nchannels));
    std::vector<unsigned char> strip(std::size_t(spec.width) * std::size_t(rows) *
                                     std::size_t(spec.nchannels));
    for (int y = 0; y < spec.height; y += rows)
      if (!ts->get_texels(h, ts->get_perthread_info(), opt, 0, spec.x, spec.x + spec.width,
                          spec.y + y, spec.y + std::min(spec.height, y + rows), 0, 1, 0,
                          spec.nchannels, TypeDesc::UINT8, strip.data())) {
        why = one_line(ts->geterror());
        return nullptr;
      }
    channels = spec.nchannels;
    return h;
  });
}

void texture_sample(void* s, void* handle, int nchannels, float u, float v, float dsdx,
                    float dtdx, float dsdy, float dtdy, float* rgb) {
  OIIO::TextureSystem* ts = system_of(s);
  OIIO::TextureOpt opt;
  opt.swrap = opt.twrap = OIIO::TextureOpt::WrapPeriodic;
  opt.fill = 0.0f;
  // Bilinear within a level, as rt2/shading/texture.h says: OIIO's default, smart bicubic,
  // uses B-spline weights when magnifying, which blur even a texel's centre with its
  // neighbours.
  opt.interpmode = OIIO::TextureOpt::InterpBilinear;
  float out[3] = {0.0f, 0.0f, 0.0f};
  // Grey images give one channel: it is replicated (fill would make G and B 0).
  const auto h = static_cast<OIIO::TextureSystem::TextureHandle*>(handle);
  const int channels = nchannels < 3 ? 1 : 3;
  if (!ts->texture(h, ts->get_perthread_info(), opt, u, v, dsdx, dtdx, dsdy, dtdy, channels, out))
    (void)ts->geterror();  // a read failure: black, and the message is dropped
  if (channels == 1) out[1] = out[2] = out[0];
  rgb[0] = out[0];
  rgb[1] = out[1];
  rgb[2] = out[2];
}

const rt2::ImageCodec kCodec{can_encode,         encode,
                             decode,             texture_system_create,
                             texture_system_destroy, texture_open,
                             texture_sample};

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
