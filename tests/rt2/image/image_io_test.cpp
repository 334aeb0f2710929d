// Image files through OpenImageIO: formats round-trip, failures leave no file behind, and
// the image comparison measures what it says.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "rt2/base/error.h"
#include "rt2/image/image_compare.h"
#include "rt2/image/image_io.h"
#include "rt2/image/srgb.h"
#include "tests/rt2/small_file_system.h"
#include "tests/rt2/temp_dir.h"

namespace rt2 {
namespace {

namespace fs = std::filesystem;

Image gradient(int w, int h) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* p = img.row(y) + 3 * x;
      p[0] = float(x) / float(w - 1);
      p[1] = float(y) / float(h - 1);
      p[2] = 0.25f;
    }
  return img;
}

TEST(ImageIo, EveryFormatRoundTripsWithinItsPrecision) {
  const test::TempDir tmp("image_io_roundtrip");
  const fs::path& d = tmp.root();
  const Image img = gradient(37, 21);
  for (const char* ext : {".png", ".exr", ".ppm", ".hdr", ".tif", ".jpg", ".bmp"}) {
    const std::string path = (d / (std::string("img") + ext)).string();
    write_image(path, img);
    const Image back = read_image(path);
    ASSERT_EQ(back.width, 37);
    ASSERT_EQ(back.height, 21);
    const std::string e = ext;
    for (std::size_t i = 0; i < img.rgb.size(); ++i) {
      if (e == ".exr" || e == ".tif") {
        ASSERT_EQ(back.rgb[i], img.rgb[i]) << ext;  // 32-bit float
      } else if (e == ".hdr") {
        // RGBE: 8-bit mantissas under the exponent of the pixel's largest channel.
        const float* px = &img.rgb[i - i % 3];
        ASSERT_NEAR(back.rgb[i], img.rgb[i], std::max({px[0], px[1], px[2]}) / 128.0f) << ext;
      } else if (e == ".jpg") {
        continue;  // lossy: judged on the whole image below
      } else {  // 8-bit sRGB: within half a step of the encoded value
        ASSERT_NEAR(srgb_encode(back.rgb[i]), srgb_encode(img.rgb[i]), 0.5f / 255.0f + 1e-6f) << ext;
      }
    }
    if (e == ".jpg") {
      EXPECT_GT(compare_images(back, img).psnr, 30.0);
    }
  }
  // No temporary files remain.
  std::size_t files = 0;
  for (const auto& e : fs::directory_iterator(d)) files += e.is_regular_file();
  EXPECT_EQ(files, 7u);
}

TEST(Srgb, EncodeAndDecodeFollowTheStandardCurve) {
  // IEC 61966-2-1: the linear segment up to 0.0031308, then 1.055 x^(1/2.4) - 0.055.
  EXPECT_NEAR(srgb_encode(0.0031308f), 0.04044994f, 1e-7);
  EXPECT_FLOAT_EQ(srgb_encode(0.001f), 0.01292f);
  EXPECT_NEAR(srgb_encode(0.18f), 0.46135613f, 1e-7);
  EXPECT_NEAR(srgb_encode(0.5f), 0.73535698f, 1e-7);
  EXPECT_EQ(srgb_encode(-1.0f), 0.0f);
  EXPECT_EQ(srgb_encode(7.0f), 1.0f);
  EXPECT_EQ(srgb_encode(std::nanf("")), 0.0f);
  // Every 8-bit level survives decode then encode.
  for (int k = 0; k <= 255; ++k) {
    const float e = float(k) / 255.0f;
    EXPECT_NEAR(srgb_encode(srgb_decode(e)), e, 1e-6f) << k;
  }
}

TEST(ImageIo, DisplayFormatsAreTaggedSrgbAndFloatFormatsLinear) {
  EXPECT_TRUE(is_linear_format("a.exr"));
  EXPECT_TRUE(is_linear_format("a.HDR"));
  EXPECT_TRUE(is_linear_format("dir.x/a.tif"));
  EXPECT_FALSE(is_linear_format("a.png"));
  EXPECT_FALSE(is_linear_format("a.jpg"));
  EXPECT_FALSE(is_linear_format("a.ppm"));
  // A mid-grey linear 0.2159 is stored as sRGB 128/255, not 55/255 (a plain clamp).
  const test::TempDir tmp("image_io_srgb");
  Image grey(2, 2);
  for (float& v : grey.rgb) v = 0.2158605f;
  write_image(tmp.path("g.ppm"), grey);
  const std::string bytes = [&] {
    std::ifstream in(tmp.path("g.ppm"), std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }();
  ASSERT_GE(bytes.size(), 12u);
  EXPECT_EQ(static_cast<unsigned char>(bytes.back()), 128);
}

TEST(ImageIo, AFullDiskFailsEveryFormatCleanly) {
  const test::SmallFileSystem disk;
  if (!disk.available()) GTEST_SKIP() << disk.why_not();
  // Noise does not compress: every format needs far more than 64 KiB.
  Image noise(300, 200);
  std::uint32_t state = 12345;
  for (float& v : noise.rgb) {
    state = state * 1664525u + 1013904223u;
    v = float(state >> 8) / float(1u << 24);
  }
  for (const char* ext : {".png", ".jpg", ".exr", ".ppm", ".tif", ".hdr", ".bmp"}) {
    const std::string path = disk.path(std::string("full") + ext);
    try {
      write_image(path, noise);
      ADD_FAILURE() << ext << ": no error";
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()), "cannot write " + path + ": No space left on device") << ext;
    }
    EXPECT_EQ(disk.entries(), 0u) << ext << ": a file was left behind";
  }
}

TEST(ImageIo, MissingFolderUnsupportedExtensionAndDirectoryTargetFailCleanly) {
  const test::TempDir tmp("image_io_bad");
  const fs::path& d = tmp.root();
  const Image img = gradient(4, 4);
  EXPECT_THROW(write_image((d / "no/such/dir/x.png").string(), img), Error);
  EXPECT_THROW(write_image((d / "x.notaformat").string(), img), Error);
  EXPECT_THROW(write_image((d / "noextension").string(), img), Error);
  fs::create_directories(d / "adir.png");
  EXPECT_THROW(write_image((d / "adir.png").string(), img), Error);
  std::size_t files = 0;
  for (const auto& e : fs::recursive_directory_iterator(d)) files += e.is_regular_file();
  EXPECT_EQ(files, 0u);
}

TEST(ImageIo, UnwritableFolderFailsAndLeavesNoFile) {
  if (::geteuid() != 0) {  // a read-only folder stops an ordinary user before writing
    const test::TempDir tmp("image_io_ro");
    const fs::path& d = tmp.root();
    ::chmod(d.c_str(), 0555);
    EXPECT_THROW(check_writable_image((d / "x.png").string()), Error);
    ::chmod(d.c_str(), 0755);
  }
  // /proc refuses new files even to root: the write itself fails, cleanly.
  EXPECT_THROW(write_image("/proc/rt2_test_image.png", gradient(4, 4)), Error);
  EXPECT_FALSE(fs::exists("/proc/rt2_test_image.png"));
}

TEST(ImageIo, ErrorsAreOneLine) {
  try {
    write_image("/nonexistent-dir-rt2/x.png", gradient(2, 2));
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    EXPECT_EQ(std::string(e.what()).rfind("cannot write /nonexistent-dir-rt2/x.png: ", 0), 0u)
        << e.what();
  }
  EXPECT_THROW(read_image("/nonexistent-dir-rt2/x.png"), Error);
}

TEST(ImageIo, ReadingRefusesDevicesPipesDirectoriesAndNonImages) {
  const test::TempDir tmp("image_io_read");
  ASSERT_EQ(::mkfifo(tmp.path("fifo.png").c_str(), 0600), 0);
  for (const std::string& p : {std::string("/dev/zero"), tmp.path("fifo.png")}) {
    try {
      read_image(p);  // would never end if it were opened
      ADD_FAILURE() << p;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(read_image(tmp.root().string()), Error);
  EXPECT_THROW(read_image(tmp.write("text.png", "this is not a PNG\n")), Error);
}

TEST(ImageCompare, IdenticalImagesHaveZeroErrorInfinitePsnrAndSsimOne) {
  const Image a = gradient(40, 30);
  const ImageError e = compare_images(a, a);
  EXPECT_EQ(e.rmse, 0.0);
  EXPECT_TRUE(std::isinf(e.psnr));
  EXPECT_NEAR(e.ssim, 1.0, 1e-12);
}

TEST(ImageCompare, RmseAndPsnrMatchTheirDefinitions) {
  const Image a = gradient(40, 30);
  Image b = a;
  for (float& v : b.rgb) v += 0.1f;  // constant offset: RMSE 0.1, PSNR 20 dB
  const ImageError e = compare_images(b, a);
  EXPECT_NEAR(e.rmse, 0.1, 1e-5);
  EXPECT_NEAR(e.psnr, 20.0, 1e-3);
  EXPECT_LT(e.ssim, 1.0);
  Image noisy = a;
  for (std::size_t i = 0; i < noisy.rgb.size(); i += 7) noisy.rgb[i] = 1.0f - noisy.rgb[i];
  EXPECT_LT(compare_images(noisy, a).ssim, e.ssim);  // structure damage costs more
  EXPECT_THROW(compare_images(gradient(4, 4), gradient(5, 4)), Error);
}

TEST(ImageCompare, EdgeErrorCountsOnlyPixelsNearTheReferencesEdges) {
  // Reference: a vertical black/white edge at x = 10 in a 20x8 image.
  Image ref(20, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 10; x < 20; ++x)
      for (int c = 0; c < 3; ++c) ref.row(y)[3 * x + c] = 1.0f;
  // An error far from the edge changes RMSE but not the edge error...
  Image flat_error = ref;
  flat_error.row(4)[3 * 2] = 0.5f;
  std::size_t n = 0;
  EXPECT_EQ(edge_rmse(flat_error, ref, n), 0.0);
  EXPECT_EQ(n, 8u * 2u);  // columns 9 and 10 see both colours in their 3x3 neighbourhood
  EXPECT_GT(compare_images(flat_error, ref).rmse, 0.0);
  // ...an error on the edge shows in both.
  Image edge_error = ref;
  for (int c = 0; c < 3; ++c) edge_error.row(3)[3 * 10 + c] = 0.5f;
  const ImageError e = compare_images(edge_error, ref);
  EXPECT_NEAR(e.edge_rmse, std::sqrt(0.25 / 16.0), 1e-9);
  EXPECT_EQ(e.edge_pixels, 16u);
}

}  // namespace
}  // namespace rt2
