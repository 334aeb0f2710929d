// Image files through OpenImageIO: formats round-trip, failures leave no file behind, and
// the image comparison measures what it says.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "rt2/error.h"
#include "rt2/image_compare.h"
#include "tests/rt2/temp_dir.h"
#include "rt2/image_io.h"

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

TEST(ImageIo, PngExrAndPpmRoundTripWithinTheirPrecision) {
  const test::TempDir tmp("image_io_roundtrip");
  const fs::path& d = tmp.root();
  const Image img = gradient(37, 21);
  for (const char* ext : {".png", ".exr", ".ppm"}) {
    const std::string path = (d / (std::string("img") + ext)).string();
    write_image(path, img);
    const Image back = read_image(path);
    ASSERT_EQ(back.width, 37);
    ASSERT_EQ(back.height, 21);
    const float tol = std::string(ext) == ".exr" ? 0.0f : 0.5f / 255.0f + 1e-6f;
    for (std::size_t i = 0; i < img.rgb.size(); ++i) ASSERT_NEAR(back.rgb[i], img.rgb[i], tol) << ext;
  }
  // No temporary files remain.
  std::size_t files = 0;
  for (const auto& e : fs::directory_iterator(d)) files += e.is_regular_file();
  EXPECT_EQ(files, 3u);
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
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir-rt2"), std::string::npos);
  }
  EXPECT_THROW(read_image("/nonexistent-dir-rt2/x.png"), Error);
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
