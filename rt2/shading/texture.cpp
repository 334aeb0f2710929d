// rt2/shading/texture.cpp — textures through the codec's TextureSystem (see texture.h).
#include "rt2/shading/texture.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <utility>

#include "rt2/base/error.h"
#include "rt2/image/image_codec.h"
#include "rt2/image/image_io.h"
#include "rt2/image/srgb.h"

namespace rt2 {

namespace {

namespace fs = std::filesystem;

// A file name extension for an embedded image's bytes (OIIO tries the extension's reader
// first, then the others).
const char* extension_of_bytes(const std::string& data) {
  if (data.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0) return ".png";
  if (data.size() >= 3 && static_cast<unsigned char>(data[0]) == 0xFF &&
      static_cast<unsigned char>(data[1]) == 0xD8)
    return ".jpg";
  return ".img";
}

std::string make_temp_dir() {
  const char* tmp = std::getenv("TMPDIR");
  std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/rt2-textures-XXXXXX";
  if (!::mkdtemp(pattern.data()))
    throw Error("cannot make a folder for embedded textures: " + pattern);
  return pattern;
}

}  // namespace

TextureSet::TextureSet(const std::vector<TextureDesc>& textures, std::uint64_t max_pixels) {
  if (textures.empty()) return;
  try {
    codec_ = &image_codec();
    system_ = codec_->texture_system_create();
    for (std::size_t i = 0; i < textures.size(); ++i) {
      const TextureDesc& t = textures[i];
      std::string file = t.path;
      if (!t.data.empty()) {
        if (temp_dir_.empty()) temp_dir_ = make_temp_dir();
        file = temp_dir_ + "/image" + std::to_string(i) + extension_of_bytes(t.data);
        std::ofstream out(file, std::ios::binary);
        out.write(t.data.data(), static_cast<std::streamsize>(t.data.size()));
        if (!out.flush()) throw Error(t.path + ": cannot write it to " + file);
      }
      const ImageHeader header = read_image_header(file, max_pixels, t.path);
      std::string why;
      void* h = codec_->texture_open(system_, file, header, why);
      if (!h) throw Error(t.path + ": cannot read texture: " + why);
      handles_.push_back(h);
      channels_.push_back(header.channels);
      srgb_.push_back(t.srgb);
    }
  } catch (...) {
    release();
    throw;
  }
}

TextureSet::~TextureSet() { release(); }

void TextureSet::release() {
  if (system_) codec_->texture_system_destroy(system_);
  system_ = nullptr;
  handles_.clear();
  if (!temp_dir_.empty()) {
    std::error_code ec;
    fs::remove_all(temp_dir_, ec);
    temp_dir_.clear();
  }
}

TextureSet::TextureSet(TextureSet&& o) noexcept { *this = std::move(o); }

TextureSet& TextureSet::operator=(TextureSet&& o) noexcept {
  if (this != &o) {
    release();
    codec_ = std::exchange(o.codec_, nullptr);
    system_ = std::exchange(o.system_, nullptr);
    handles_ = std::move(o.handles_);
    channels_ = std::move(o.channels_);
    srgb_ = std::move(o.srgb_);
    temp_dir_ = std::exchange(o.temp_dir_, std::string());
    o.handles_.clear();
  }
  return *this;
}

vec4 TextureSet::sample(std::uint32_t index, float u, float v, float width) const {
  float rgb[3];
  // rt2's v has row 0 at v = 1; OIIO's t has row 0 at t = 0.
  codec_->texture_sample(system_, handles_[index], channels_[index], u, 1.0f - v, width, 0.0f,
                         0.0f, width, rgb);
  if (srgb_[index])
    for (float& c : rgb) c = srgb_decode(c);
  return vec4(rgb[0], rgb[1], rgb[2]);
}

long long TextureSet::tiles_made() const {
  return system_ ? codec_->texture_tiles_made(system_) : 0;
}

}  // namespace rt2
