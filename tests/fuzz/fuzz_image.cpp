// tests/fuzz/fuzz_image.cpp — libFuzzer target for the image files a scene names: the input's
// first byte chooses the use (bit 0: a texture, or the environment) and the file's extension
// (the other bits: .png .jpg .exr .hdr .tif .bmp .ppm .tga .img), the rest is the file, read
// as compiling a scene reads it under a limit of 2^20 pixels. A texture (of at most 2048
// rows) is opened with TextureSet (header checks, every texel and mip level read) and looked
// up over a grid at several footprints; an environment goes through read_image_header and
// read_image. A one-line rt2::Error is the expected failure. Built and run by scripts/fuzz
// (--target image), the codec instrumented too; OpenImageIO and its libraries are not.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <iterator>
#include <string>
#include <string_view>

#include "rt2/image/image_io.h"
#include "rt2/shading/texture.h"
#include "tests/fuzz/fuzz_io.h"

namespace {

constexpr const char* kExtensions[] = {".png", ".jpg", ".exr", ".hdr", ".tif",
                                       ".bmp", ".ppm", ".tga", ".img"};
constexpr std::uint64_t kMaxPixels = std::uint64_t(1) << 20;
constexpr std::int64_t kMaxTextureRows = 2048;

void use(const std::string& path, bool environment) {
  if (environment) {
    (void)rt2::read_image_header(path, kMaxPixels, path);
    (void)rt2::read_image(path, kMaxPixels);
    return;
  }
  // OpenImageIO 2.4's read_scanlines allocates 64 MiB per call, and the texture cache calls
  // it once per band of 64 rows of a file without tiles; under ASan each call poisons
  // 16 MiB of shadow memory, so a texture of thousands of rows would time out without a
  // bug. Taller ones are only checked from their header here.
  if (rt2::read_image_header(path, kMaxPixels, path).height > kMaxTextureRows) return;
  const rt2::TextureSet set({rt2::TextureDesc{path, {}, true}}, kMaxPixels);
  for (const float width : {0.0f, 0.01f, 0.3f, 2.0f})
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x)
        (void)set.sample(0, (float(x) + 0.25f) / 4.0f, (float(y) + 0.75f) / 4.0f, width);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  rt2::fuzz::silence_warnings();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string_view input(reinterpret_cast<const char*>(data) + 1, size - 1);
  const bool environment = data[0] & 1;
  const char* ext = kExtensions[(data[0] >> 1) % std::size(kExtensions)];
  const auto path = rt2::fuzz::scratch("image") / (std::string("image") + ext);
  rt2::fuzz::write_file(path, input);
  try {
    use(path.string(), environment);
  } catch (const rt2::Error& e) {
    if (std::string_view(e.what()).find_first_of("\r\n") != std::string_view::npos) {
      std::cout << "rt2::Error message is not one line: " << e.what() << std::endl;
      std::abort();
    }
  }
  return 0;
}
