// rt2/image/image_codec_oiio.cpp — the image codec on OpenImageIO, built as
// lib/librt2_image_codec.so (see image_codec.h). The only file of rt2 that includes OIIO.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/texture.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <memory>
#include <utility>
#include <vector>

#include "rt2/image/image_codec.h"

namespace {

using OIIO::ImageInput;
using OIIO::ImageOutput;
using OIIO::ImageSpec;
using OIIO::TypeDesc;
using rt2::ImageHeader;
using rt2::kMaxMipLevels;
using rt2::kMaxSubimages;

// OIIO's messages on one line, and short: a broken file can make it repeat the same
// complaint for every tile it tried.
std::string one_line(std::string s) {
  // control characters too: a message may quote bytes of the file
  for (char& c : s)
    if ((c >= 0 && c < 0x20) || c == 0x7F) c = ' ';
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

// The readers rt2 lets read a file, and how a file shows it is theirs: its first bytes.
// Targa has no signature (length 0); it is recognised by the extension .tga alone.
struct Format {
  const char* name;       // OIIO's reader
  const char* signature;  // the file's first bytes
  std::size_t length;
};
constexpr Format kFormats[] = {
    {"png", "\x89PNG\r\n\x1a\n", 8}, {"jpeg", "\xff\xd8\xff", 3},
    {"openexr", "\x76\x2f\x31\x01", 4}, {"hdr", "#?", 2},
    {"tiff", "II*\0", 4}, {"tiff", "MM\0*", 4}, {"tiff", "II+\0", 4}, {"tiff", "MM\0+", 4},
    {"bmp", "BM", 2}, {"pnm", "P1", 2}, {"pnm", "P2", 2}, {"pnm", "P3", 2}, {"pnm", "P4", 2},
    {"pnm", "P5", 2}, {"pnm", "P6", 2}, {"pnm", "PF", 2}, {"pnm", "Pf", 2}, {"targa", "", 0}};

// The reader for the regular file `path`, from its first bytes; "" and `why` otherwise.
std::string format_of(const std::string& path, std::string& why) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    why = std::strerror(errno);
    return "";
  }
  struct stat st {};
  char head[8] = {};
  ssize_t got = 0;
  const bool regular = ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode);
  if (regular) got = ::read(fd, head, sizeof head);
  ::close(fd);
  if (!regular) {
    why = "not a regular file";
    return "";
  }
  for (const Format& f : kFormats)
    if (f.length > 0 && got >= ssize_t(f.length) && std::memcmp(head, f.signature, f.length) == 0)
      return f.name;
  const std::string ext = OIIO::Filesystem::extension(path);
  if (OIIO::Strutil::iequals(ext, ".tga")) return "targa";
  why = "not a PNG, JPEG, OpenEXR, Radiance HDR, TIFF, BMP, PNM or Targa image";
  return "";
}

// An ImageInput::Creator per format, for the texture cache: it opens a file with the
// reader probe() chose, never by the file's name.
template <std::size_t I>
ImageInput* create_reader() {
  return ImageInput::create(kFormats[I].name).release();
}
template <std::size_t... I>
constexpr auto creators(std::index_sequence<I...>) {
  return std::array<ImageInput::Creator, sizeof...(I)>{create_reader<I>...};
}
constexpr auto kCreators = creators(std::make_index_sequence<std::size(kFormats)>());

ImageInput::Creator creator_of(const std::string& format) {
  for (std::size_t i = 0; i < std::size(kFormats); ++i)
    if (format == kFormats[i].name) return kCreators[i];
  return nullptr;
}

// `path` opened with the reader `format`; nullptr and `why` when it cannot be.
std::unique_ptr<ImageInput> open_as(const std::string& path, const std::string& format,
                                    std::string& why) {
  auto in = ImageInput::create(format);
  if (!in) {
    why = one_line(OIIO::geterror());
    return nullptr;
  }
  ImageSpec spec;
  if (!in->open(path, spec)) {
    why = one_line(in->geterror());
    return nullptr;
  }
  return in;
}

void fill_header(const ImageSpec& spec, ImageHeader& h) {
  h.width = spec.width;
  h.height = spec.height;
  h.depth = spec.depth;
  h.x = spec.x;
  h.y = spec.y;
  h.full_width = spec.full_width;
  h.full_height = spec.full_height;
  h.full_x = spec.full_x;
  h.full_y = spec.full_y;
  h.channels = spec.nchannels;
  h.deep = spec.deep;
}

// Whether `spec` is still what the header said (the file may change between reads).
bool matches(const ImageSpec& spec, const ImageHeader& h) {
  ImageHeader now;
  fill_header(spec, now);
  return now.width == h.width && now.height == h.height && now.depth == h.depth &&
         now.channels == h.channels && now.deep == h.deep && now.x == h.x && now.y == h.y;
}

std::string probe_loudly(const std::string& path, ImageHeader& header) {
  std::string why;
  header = ImageHeader{};
  header.format = format_of(path, why);
  if (header.format.empty()) return why;
  auto in = open_as(path, header.format, why);
  if (!in) return why;
  fill_header(in->spec(), header);
  // Counted, not listed: a TIFF can chain thousands of directories.
  header.miplevels = 1;
  while (header.miplevels <= kMaxMipLevels && in->seek_subimage(0, header.miplevels))
    ++header.miplevels;
  header.subimages = 1;
  while (header.subimages <= kMaxSubimages && in->seek_subimage(header.subimages, 0))
    ++header.subimages;
  (void)in->geterror();  // the failed seek's
  return "";
}

std::string decode_loudly(const std::string& path, const ImageHeader& header,
                          std::vector<float>& rgb, bool& srgb) {
  std::string why;
  auto in = open_as(path, header.format, why);
  if (!in) return why;
  const ImageSpec& spec = in->spec();
  if (!matches(spec, header)) return "the file changed while it was read";
  // The first three channels (or fewer) straight into rgb, 3 floats apart.
  const int take = std::min(spec.nchannels, 3);
  const std::size_t n = std::size_t(spec.width) * std::size_t(spec.height);
  rgb.assign(n * 3, 0.0f);
  // OIIO 2.4's TIFF reader records a strip it cannot read (one past the end of the file)
  // as an error but reports success, leaving black pixels: an error is a failure.
  const bool read = in->read_image(0, 0, 0, take, TypeDesc::FLOAT, rgb.data(), 3 * sizeof(float));
  const std::string error = in->geterror();
  if (!read || !error.empty()) return one_line(error);
  for (std::size_t i = 0; i < n; ++i)
    for (int c = take; c < 3; ++c) rgb[3 * i + c] = rgb[3 * i + take - 1];
  const std::string cs = spec.get_string_attribute("oiio:ColorSpace");
  const bool integer = spec.format.basetype == TypeDesc::UINT8 ||
                       spec.format.basetype == TypeDesc::UINT16;
  srgb = integer && !OIIO::Strutil::iequals(cs, "linear");
  return "";
}

// Runs `f` with the process's stderr pointed at /dev/null: libpng and libjpeg print their
// own complaints there before OIIO reports the error rt2 turns into its one line. Only for
// what runs before or after rendering, on one thread (file descriptors are per process).
// With RT2_IMAGE_STDERR=1 in the environment stderr stays: the libraries' messages, and a
// sanitizer's report of a crash inside them (scripts/fuzz sets it), are seen.
template <typename F>
auto quietly(F&& f) {
  static const bool keep = [] {
    const char* v = std::getenv("RT2_IMAGE_STDERR");
    return v && std::string(v) == "1";
  }();
  if (keep) return f();
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

std::string probe(const std::string& path, ImageHeader& header) {
  return quietly([&] { return probe_loudly(path, header); });
}

std::string decode(const std::string& path, const ImageHeader& header, std::vector<float>& rgb,
                   bool& srgb) {
  return quietly([&] { return decode_loudly(path, header, rgb, srgb); });
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

// Reads every texel of the level `miplevel` through the cache, in blocks of at most 4 MiB.
bool read_level(OIIO::TextureSystem* ts, OIIO::TextureSystem::TextureHandle* h,
                const ImageSpec& level, int miplevel) {
  using I = std::int64_t;
  const I nc = level.nchannels, w = level.width, ht = level.height;
  const I cols = std::min<I>(w, std::max<I>(1, (1 << 22) / nc));
  const I rows = std::min<I>(ht, std::max<I>(1, (1 << 22) / (cols * nc)));
  std::vector<unsigned char> block(std::size_t(cols * rows * nc));
  OIIO::TextureOpt opt;
  OIIO::TextureSystem::Perthread* thread = ts->get_perthread_info();
  for (I y = 0; y < ht; y += rows)
    for (I x = 0; x < w; x += cols) {
      const int x0 = int(level.x + x), x1 = int(level.x + std::min(w, x + cols));
      const int y0 = int(level.y + y), y1 = int(level.y + std::min(ht, y + rows));
      if (!ts->get_texels(h, thread, opt, miplevel, x0, x1, y0, y1, 0, 1, 0, int(nc),
                          TypeDesc::UINT8, block.data()))
        return false;
    }
  return true;
}

// OIIO 2.4's TIFF reader reports success for a strip it cannot read (one past the end of
// the file), recording an error and leaving black pixels, and the texture cache does not
// look at that error: a TIFF texture's first channel is read once more, a band of rows at a
// time (of whole tiles: OIIO 2.4's read_scanlines divides by zero on a tiled TIFF), to find
// it. "" or the error.
std::string tiff_read_error(const std::string& path, const ImageHeader& header) {
  std::string why;
  auto in = open_as(path, header.format, why);
  if (!in) return why;
  const ImageSpec& spec = in->spec();
  if (!matches(spec, header)) return "the file changed while it was read";
  const bool tiled = spec.tile_width > 0 && spec.tile_height > 0;
  const std::int64_t width = tiled ? (header.width + spec.tile_width - 1) / spec.tile_width *
                                         std::int64_t(spec.tile_width)
                                   : header.width;
  const std::int64_t unit = tiled ? spec.tile_height : 1;
  const std::int64_t rows = std::min<std::int64_t>(
      (header.height + unit - 1) / unit * unit,
      unit * std::max<std::int64_t>(1, (1 << 22) / (width * unit)));
  std::vector<float> band(std::size_t(rows * width));
  for (std::int64_t y = 0; y < header.height; y += rows) {
    const int y0 = spec.y + int(y), y1 = spec.y + int(std::min(header.height, y + rows));
    const bool read =
        tiled ? in->read_tiles(0, 0, spec.x, spec.x + spec.width, y0, y1, spec.z, spec.z + 1, 0, 1,
                               TypeDesc::FLOAT, band.data())
              : in->read_scanlines(0, 0, y0, y1, 0, 0, 1, TypeDesc::FLOAT, band.data());
    why = in->geterror();
    if (!read || !why.empty()) return why.empty() ? "cannot read its pixels" : why;
  }
  return "";
}

void* texture_open(void* s, const std::string& path, const ImageHeader& header, std::string& why) {
  OIIO::TextureSystem* ts = system_of(s);
  return quietly([&]() -> void* {
    (void)ts->geterror();  // errors left by an earlier texture
    (void)ts->imagecache()->geterror();
    const OIIO::ustring name(path);
    const ImageInput::Creator creator = creator_of(header.format);
    // replacing a file of this name read before (by an earlier scene): it may have changed
    if (!creator || !ts->imagecache()->add_file(name, creator, nullptr, /*replace=*/true)) {
      why = creator ? one_line(ts->imagecache()->geterror()) : "no reader for " + header.format;
      return nullptr;
    }
    OIIO::TextureSystem::TextureHandle* h = ts->get_texture_handle(name);
    ImageSpec spec;
    if (!h || !ts->get_imagespec(h, nullptr, 0, spec)) {
      why = one_line(ts->geterror());
      return nullptr;
    }
    if (!matches(spec, header)) {
      why = "the file changed while it was read";
      return nullptr;
    }
    // Every texel of every level now: a file truncated or corrupt past its header is an
    // error here and not black texels (and a complaint per tile) while rendering, and the
    // first frame neither reads the file nor makes the mip levels. The cache keeps them.
    // An error recorded while reading is a failure, even when the read reports success
    // (see decode).
    int levels = 0;
    if (!ts->get_texture_info(h, nullptr, 0, OIIO::ustring("miplevels"), OIIO::TypeInt, &levels))
      levels = 1;
    for (int m = 0; m < levels; ++m) {
      const ImageSpec* level = ts->imagecache()->imagespec(name, 0, m);
      const bool read = level && read_level(ts, h, *level, m);
      why = ts->geterror() + ts->imagecache()->geterror();
      if (!read || !why.empty()) {
        why = one_line(why);
        return nullptr;
      }
    }
    if (header.format == "tiff") {
      why = tiff_read_error(path, header);
      if (!why.empty()) {
        why = one_line(why);
        return nullptr;
      }
    }
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

long long texture_tiles_made(void* s) {
  int tiles = 0;
  system_of(s)->imagecache()->getattribute("stat:tiles_created", OIIO::TypeInt, &tiles);
  return tiles;
}

const rt2::ImageCodec kCodec{can_encode,         encode,
                             probe,              decode,
                             texture_system_create, texture_system_destroy,
                             texture_open,       texture_sample,
                             texture_tiles_made};

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
