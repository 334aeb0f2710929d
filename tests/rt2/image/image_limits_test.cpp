// The checks made on an image file before any of its pixels is read (image_io.h's
// read_image_header), as textures and environments meet them when a scene is compiled: the
// pixel limit of Scene::assets, sizes that overflow or are empty, special files, formats rt2
// does not read, and an environment larger than the free memory. The files are written here,
// most by hand: small files whose headers declare huge images.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "rt2/base/error.h"
#include "rt2/image/image_codec.h"
#include "rt2/image/image_io.h"
#include "rt2/render/compiled_scene.h"
#include "tests/rt2/error_of.h"
#include "tests/rt2/temp_dir.h"

namespace rt2 {
namespace {

using test::error_of;
using test::TempDir;

std::uint32_t crc32(const std::string& bytes) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (const unsigned char b : bytes) {
    c ^= b;
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
  }
  return ~c;
}

std::string be32(std::uint32_t v) {
  return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
}

std::string png_chunk(const std::string& type, const std::string& data) {
  return be32(std::uint32_t(data.size())) + type + data + be32(crc32(type + data));
}

// A PNG whose header declares width x height RGB pixels, followed by the first row's bytes
// (zeros, in a stored deflate block) and nothing else: the rest is missing.
std::string png_declaring(std::uint32_t width, std::uint32_t height) {
  const std::string ihdr = be32(width) + be32(height) + std::string("\x08\x02\x00\x00\x00", 5);
  const std::uint16_t n = 64;
  const std::string idat = std::string("\x78\x01\x00", 3) + char(n & 0xFF) + char(n >> 8) +
                           char(~n & 0xFF) + char((~n >> 8) & 0xFF) + std::string(n, '\0');
  return std::string("\x89PNG\r\n\x1a\n", 8) + png_chunk("IHDR", ihdr) + png_chunk("IDAT", idat);
}

// A Radiance HDR whose header declares width x height pixels, followed by one pixel.
std::string hdr_declaring(std::uint64_t width, std::uint64_t height) {
  return "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(height) + " +X " +
         std::to_string(width) + "\n" + std::string(4, '\x80');
}

// Compiles a scene of nothing but `textures` and, unless "", the environment image
// `environment`, under the pixel limit `max_pixels`.
CompiledScene compile_images(const std::vector<TextureDesc>& textures,
                             const std::string& environment, std::uint64_t max_pixels) {
  Scene scene;
  scene.textures = textures;
  if (!environment.empty()) scene.environment = EnvironmentDesc{.image = environment};
  scene.assets.max_image_pixels = max_pixels;
  return CompiledScene::compile(scene, BvhConfig{});
}

constexpr std::uint64_t kDefaultLimit = AssetPolicy{}.max_image_pixels;

// The example: today's 1.2 MB PNG of 20000 x 20000 black pixels took minutes to
// open as a texture; its header alone now refuses it. Here only its header and first row.
TEST(ImageLimits, AnImageOverThePixelLimitIsRefusedFromItsHeaderInUnderASecond) {
  const TempDir dir("image_limits");
  const std::string big = png_declaring(20000, 20000);
  const std::string file = dir.write("big.png", big);
  const std::string limit =
      ": 20000 x 20000 pixels is more than the limit of 268435456 (--max-texture-pixels "
      "raises it)";
  (void)image_codec();  // loaded before the clock starts
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(error_of([&] { compile_images({TextureDesc{file, {}, true}}, "", kDefaultLimit); }),
            file + limit);
  EXPECT_EQ(error_of([&] {
              compile_images({TextureDesc{"x.glb:image 2", big, true}}, "", kDefaultLimit);
            }),
            "x.glb:image 2" + limit);
  EXPECT_EQ(error_of([&] { compile_images({}, file, kDefaultLimit); }), file + limit);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 1.0) << "three refusals";
}

// The limit is Scene::assets.max_image_pixels, inclusive: a 16 x 16 image is read under a
// limit of 256 and refused under 255, as a texture and as an environment.
TEST(ImageLimits, TheLimitIsTheScenesMaxImagePixels) {
  const TempDir dir("image_limits");
  Image img(16, 16);
  for (float& v : img.rgb) v = 0.5f;
  const std::string png = dir.path("t.png"), hdr = dir.path("e.hdr");
  write_image(png, img);
  write_image(hdr, img);
  EXPECT_EQ(compile_images({TextureDesc{png, {}, true}}, hdr, 256).textures.size(), 1u);
  EXPECT_EQ(error_of([&] { compile_images({TextureDesc{png, {}, true}}, "", 255); }),
            png + ": 16 x 16 pixels is more than the limit of 255 (--max-texture-pixels raises it)");
  EXPECT_EQ(error_of([&] { compile_images({}, hdr, 255); }),
            hdr + ": 16 x 16 pixels is more than the limit of 255 (--max-texture-pixels raises it)");
}

// width x height is counted in 64 bits: 2^31 - 1 squared wraps to 1 in 32 bits.
TEST(ImageLimits, WidthTimesHeightDoesNotOverflow) {
  const TempDir dir("image_limits");
  const std::string file = dir.write("wrap.hdr", hdr_declaring(2147483647, 2147483647));
  const std::string msg = error_of([&] { compile_images({}, file, kDefaultLimit); });
  EXPECT_EQ(msg.rfind(file + ": 2147483647 x 2147483647 pixels is more than the limit", 0), 0u)
      << msg;
}

// With the limit lifted, an environment declaring 2^18 x 2^18 texels is refused because it
// would not fit in memory, before anything of its size is allocated; one of 2^30 x 2^30 is
// more than rt2 reads whatever the limit.
TEST(ImageLimits, AnEnvironmentLargerThanTheFreeMemoryIsRefusedBeforeReading) {
  const TempDir dir("image_limits");
  const std::string file = dir.write("huge.hdr", hdr_declaring(1 << 18, 1 << 18));
  const std::string msg = error_of([&] { compile_images({}, file, kNoPixelLimit); });
  EXPECT_EQ(msg.rfind(file + ": a 262144 x 262144 environment needs ", 0), 0u) << msg;
  EXPECT_NE(msg.find("GiB of memory, but only"), std::string::npos) << msg;
  const std::string huger = dir.write("huger.hdr", hdr_declaring(1 << 30, 1 << 30));
  EXPECT_EQ(error_of([&] { compile_images({}, huger, kNoPixelLimit); }),
            huger + ": more than 2^36 pixels, the most rt2 reads whatever the limit");
}

// Empty sizes, and sides beyond 2^30, are refused from the header.
TEST(ImageLimits, ZeroAndAbsurdSizesAreRefused) {
  const TempDir dir("image_limits");
  for (const auto& [name, bytes] :
       {std::pair{std::string("wide.hdr"), hdr_declaring(std::uint64_t(1) << 31, 1)},
        std::pair{std::string("zero.pgm"), std::string("P5\n0 5\n255\n")},
        std::pair{std::string("zero.hdr"), hdr_declaring(0, 7)}}) {
    SCOPED_TRACE(name);
    const std::string file = dir.write(name, bytes);
    const std::string msg = error_of([&] { compile_images({}, file, kNoPixelLimit); });
    EXPECT_EQ(msg.rfind(file + ": ", 0), 0u) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

// Directories, pipes, devices and empty files are refused before they are opened (a pipe
// or /dev/zero would never end), as textures and as environments.
TEST(ImageFiles, DirectoriesPipesDevicesAndEmptyFilesAreOneLineErrors) {
  const TempDir dir("image_files");
  const std::string fifo = dir.path("fifo.png");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string empty = dir.write("empty.png", "");
  for (const auto& [file, why] :
       {std::pair{dir.root().string(), std::string("is a directory")},
        std::pair{fifo, std::string("not a regular file (a device or a pipe)")},
        std::pair{std::string("/dev/zero"), std::string("not a regular file (a device or a pipe)")},
        std::pair{empty, std::string("is empty")},
        std::pair{dir.path("missing.png"), std::string("No such file or directory")}}) {
    SCOPED_TRACE(file);
    EXPECT_EQ(error_of([&] { compile_images({TextureDesc{file, {}, true}}, "", kDefaultLimit); }),
              file + ": " + why);
    EXPECT_EQ(error_of([&] { compile_images({}, file, kDefaultLimit); }), file + ": " + why);
  }
}

// The reader follows the file's first bytes among PNG, JPEG, OpenEXR, Radiance HDR, TIFF,
// BMP, PNM and Targa: a GIF is refused whatever its name, a PNG named .jpg is read.
TEST(ImageFiles, OnlyKnownFormatsAreReadWhateverTheirName) {
  const TempDir dir("image_files");
  const std::string gif = dir.write(
      "one.png", std::string("GIF89a\x01\x00\x01\x00\x80\x00\x00\xff\xff\xff\x00\x00\x00,\x00\x00"
                             "\x00\x00\x01\x00\x01\x00\x00\x02\x02\x44\x01\x00;", 35));
  EXPECT_EQ(error_of([&] { compile_images({TextureDesc{gif, {}, true}}, "", kDefaultLimit); }),
            gif + ": cannot read image: not a PNG, JPEG, OpenEXR, Radiance HDR, TIFF, BMP, PNM or "
                  "Targa image");
  Image img(2, 2);
  write_image(dir.path("real.png"), img);
  std::filesystem::rename(dir.path("real.png"), dir.path("named.jpg"));
  EXPECT_EQ(compile_images({TextureDesc{dir.path("named.jpg"), {}, true}}, dir.path("named.jpg"),
                           kDefaultLimit)
                .textures.size(),
            1u);
}

// Under ASan each band of 64 rows OIIO 2.4's texture cache reads from a file costs a 64 MiB
// allocation that ASan poisons: the tall texture is shorter there.
#if defined(__SANITIZE_ADDRESS__)
constexpr int kTall = 2000;
#else
constexpr int kTall = 100000;
#endif

// Images one texel wide or tall, 1 x 1 and 100,000 on a side, written as files, compile as
// environments (a 1 x 100000 .hdr crashed rt2cpr) and as textures, and the environment
// shows their colour.
TEST(ImageFiles, ThinWideAndTallImagesCompileAsEnvironmentsAndTextures) {
  const TempDir dir("image_files");
  for (const auto& [w, h] : {std::pair{1, 100000}, std::pair{100000, 1}, std::pair{1, 1}}) {
    SCOPED_TRACE(std::to_string(w) + " x " + std::to_string(h));
    Image img(w, h);
    for (std::size_t i = 0; i < img.rgb.size(); i += 3) {
      img.rgb[i] = 0.25f;
      img.rgb[i + 1] = 0.5f;
      img.rgb[i + 2] = 1.0f;
    }
    const std::string hdr = dir.path("e.hdr"), png = dir.path("t.png");
    write_image(hdr, img);
    Image texture(w, std::min(h, kTall));
    texture.rgb.assign(img.rgb.begin(), img.rgb.begin() + std::ptrdiff_t(texture.rgb.size()));
    write_image(png, texture);
    const CompiledScene c = compile_images({TextureDesc{png, {}, false}}, hdr, kDefaultLimit);
    for (const vec4& d : {vec4(0, 1, 0), vec4(0, -1, 0), vec4(1, 0, 0), vec4(0.6f, 0, -0.8f)}) {
      const vec4 r = c.environment.radiance(d), e = c.environment.irradiance(d);
      const vec4 s = c.environment.specular(d, 0.5f);
      for (int k = 0; k < 3; ++k) {
        const float want = img.rgb[std::size_t(k)];
        EXPECT_NEAR(r[k], want, 0.02f * want);
        EXPECT_NEAR(e[k], want, 0.02f * want);
        EXPECT_NEAR(s[k], want, 0.02f * want);
      }
    }
  }
}

}  // namespace
}  // namespace rt2
