// Textures (rt2/shading/texture.h): what TextureSet::sample returns for images written here with
// write_image (sRGB-encoded 8-bit PNGs) or by hand: texel colours, the v convention, wrapping,
// colour spaces, grey images, embedded images and their temporary folder, filtering over a
// footprint, and the errors of images that cannot be opened.
#include "rt2/shading/texture.h"

#include <gtest/gtest.h>
#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#endif

#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "rt2/base/error.h"
#include "rt2/image/image_io.h"
#include "rt2/image/srgb.h"
#include "tests/rt2/error_of.h"
#include "tests/rt2/temp_dir.h"

namespace rt2 {
namespace {

namespace fs = std::filesystem;
using test::error_of;
using test::TempDir;

// 4 x 2 texels of distinct linear colours; row 0 is the image's top row.
constexpr int kW = 4, kH = 2;
const float kTexels[kH][kW][3] = {
    {{1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 1.0f}, {0.5f, 0.5f, 0.5f}},
    {{0.2f, 0.4f, 0.8f}, {1.0f, 1.0f, 0.0f}, {0.05f, 0.6f, 0.3f}, {0.9f, 0.1f, 0.7f}},
};

std::string write_texel_png(const TempDir& dir, const std::string& name = "t.png") {
  Image img(kW, kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      for (int c = 0; c < 3; ++c) img.row(y)[3 * x + c] = kTexels[y][x][c];
  const std::string path = dir.path(name);
  write_image(path, img);
  return path;
}

// The texture coordinates of texel (x, y)'s centre: u = (x + 1/2) / width, and, with image
// row 0 at v = 1, v = 1 - (y + 1/2) / height (row 0: v = 0.75, row 1: v = 0.25 here).
float u_of(int x) { return (float(x) + 0.5f) / float(kW); }
float v_of(int y) { return 1.0f - (float(y) + 0.5f) / float(kH); }

// Equal after 8-bit sRGB encoding: within half a step of the encoded value.
void expect_same_encoded(const vec4& got, const float want[3], const std::string& where) {
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(srgb_encode(got[c]), srgb_encode(want[c]), 0.5f / 255.0f + 1e-4f)
        << where << " channel " << c << ": got " << got[c] << ", want " << want[c];
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string at(int x, int y) { return "texel " + std::to_string(x) + "," + std::to_string(y); }

TEST(Texture, TexelCentresGiveTheWrittenLinearColours) {
  const TempDir dir("texture");
  const TextureSet set({TextureDesc{write_texel_png(dir), {}, true}});
  ASSERT_EQ(set.size(), 1u);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) expect_same_encoded(set.sample(0, u_of(x), v_of(y), 0.0f), kTexels[y][x], at(x, y));
}

// Row 0 of the image is at v = 1 (OBJ's convention): v = 0.75 is the top row, v = 0.25 the
// bottom one; a flipped v would swap them.
TEST(Texture, ImageRowZeroIsAtVOne) {
  const TempDir dir("texture");
  const TextureSet set({TextureDesc{write_texel_png(dir), {}, true}});
  const vec4 top = set.sample(0, u_of(0), 0.75f, 0.0f);
  const vec4 bottom = set.sample(0, u_of(0), 0.25f, 0.0f);
  expect_same_encoded(top, kTexels[0][0], "v = 0.75");      // red
  expect_same_encoded(bottom, kTexels[1][0], "v = 0.25");   // (0.2, 0.4, 0.8)
  EXPECT_GT(top[0], bottom[0]);
}

TEST(Texture, CoordinatesRepeatOutsideTheUnitSquare) {
  const TempDir dir("texture");
  const TextureSet set({TextureDesc{write_texel_png(dir), {}, true}});
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      for (const float du : {1.0f, -1.0f, 3.0f})
        for (const float dv : {0.0f, 1.0f, -2.0f})
          expect_same_encoded(set.sample(0, u_of(x) + du, v_of(y) + dv, 0.0f), kTexels[y][x],
                              at(x, y) + " shifted by " + std::to_string(du) + "," +
                                  std::to_string(dv));
}

// Linear data (srgb = false) is returned as stored: the file's sRGB-encoded values.
TEST(Texture, LinearTexturesAreNotDecoded) {
  const TempDir dir("texture");
  const TextureSet set({TextureDesc{write_texel_png(dir), {}, false}});
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const vec4 got = set.sample(0, u_of(x), v_of(y), 0.0f);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(got[c], srgb_encode(kTexels[y][x][c]), 0.5f / 255.0f + 1e-4f)
            << at(x, y) << " channel " << c;
    }
}

// A binary PGM (one channel): 2 x 1 texels of 51 and 204, i.e. 0.2 and 0.8.
TEST(Texture, GreyImagesAreReplicatedToRgb) {
  const TempDir dir("texture");
  const std::string path = dir.write("g.pgm", std::string("P5\n2 1\n255\n") + char(51) + char(204));
  const TextureSet set({TextureDesc{path, {}, false}});
  const vec4 left = set.sample(0, 0.25f, 0.5f, 0.0f), right = set.sample(0, 0.75f, 0.5f, 0.0f);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(left[c], 0.2f, 1e-4f) << c;
    EXPECT_NEAR(right[c], 0.8f, 1e-4f) << c;
  }
}

// Sets TMPDIR for the scope, restoring what it was.
class ScopedTmpdir {
 public:
  explicit ScopedTmpdir(const std::string& value) {
    if (const char* old = std::getenv("TMPDIR")) old_ = old;
    ::setenv("TMPDIR", value.c_str(), 1);
  }
  ~ScopedTmpdir() {
    if (old_)
      ::setenv("TMPDIR", old_->c_str(), 1);
    else
      ::unsetenv("TMPDIR");
  }
  ScopedTmpdir(const ScopedTmpdir&) = delete;
  ScopedTmpdir& operator=(const ScopedTmpdir&) = delete;

 private:
  std::optional<std::string> old_;
};

// The rt2-textures-* folders in `dir`.
std::vector<fs::path> texture_folders(const fs::path& dir) {
  std::vector<fs::path> found;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().starts_with("rt2-textures-")) found.push_back(e.path());
  return found;
}

TEST(Texture, EmbeddedImagesSampleLikeFilesAndTheirFolderGoesWithTheSet) {
  const TempDir dir("texture");
  const std::string bytes = slurp(write_texel_png(dir));
  ASSERT_FALSE(bytes.empty());
  const fs::path tmp = dir.root() / "tmp";
  fs::create_directories(tmp);
  const ScopedTmpdir scoped(tmp.string());
  {
    TextureSet set({TextureDesc{"x.glb:image 0", bytes, true}});
    const std::vector<fs::path> folders = texture_folders(tmp);
    ASSERT_EQ(folders.size(), 1u) << "the embedded image is written under $TMPDIR";
    EXPECT_FALSE(fs::is_empty(folders[0]));
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x)
        expect_same_encoded(set.sample(0, u_of(x), v_of(y), 0.0f), kTexels[y][x], at(x, y));
    // Moving the set moves the folder's ownership: it stays until the new owner goes.
    const TextureSet moved(std::move(set));
    EXPECT_EQ(texture_folders(tmp).size(), 1u);
  }
  EXPECT_TRUE(texture_folders(tmp).empty()) << "the temporary folder is removed with the set";
}

// An image that cannot be opened is an rt2::Error of one line starting with its path (for an
// embedded one, its name), and nothing is left in the temporary folder.
// Allocations made while one exists are not reported as leaks (the asan build).
struct LeakCheckOff {
#if defined(__SANITIZE_ADDRESS__)
  LeakCheckOff() { __lsan_disable(); }
  ~LeakCheckOff() { __lsan_enable(); }
#endif
};

TEST(Texture, UnreadableImagesAreOneLineErrorsStartingWithTheirPath) {
  const TempDir dir("texture");
  const fs::path tmp = dir.root() / "tmp";
  fs::create_directories(tmp);
  const ScopedTmpdir scoped(tmp.string());
  const std::string good = write_texel_png(dir);
  const std::string missing = dir.path("missing.png");
  const std::string garbage = dir.write("garbage.png", "this is not a PNG at all\n");
  const std::string folder = dir.path("folder.png");
  fs::create_directories(folder);
  // a whole header and the first rows, the rest cut off: an error when the scene is
  // compiled, not black texels while rendering
  Image big(256, 256);
  for (std::size_t i = 0; i < big.rgb.size(); ++i) big.rgb[i] = float((i * 7919) % 256) / 255.0f;
  const std::string whole = dir.path("whole.png");
  write_image(whole, big);
  std::string bytes;
  {
    std::ifstream in(whole, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  const std::string truncated = dir.write("truncated.png", bytes.substr(0, bytes.size() / 3));
  for (const TextureDesc& t : {TextureDesc{missing, {}, true}, TextureDesc{garbage, {}, true},
                               TextureDesc{folder, {}, false}, TextureDesc{truncated, {}, true},
                               TextureDesc{"y.glb:image 3", "\x89PNG\r\n\x1a\ngarbage", true}}) {
    SCOPED_TRACE(t.path);
    // OIIO 2.4's PNG reader leaks a copy of its error message when libpng fails inside a
    // file that starts like a PNG (libpng's longjmp skips its destructor): not rt2's to free.
    [[maybe_unused]] const LeakCheckOff oiio_leaks;
    // after a good texture, so that what was opened before is released
    const std::string msg =
        error_of([&] { const TextureSet set({TextureDesc{good, {}, true}, t}); });
    EXPECT_EQ(msg.rfind(t.path + ": ", 0), 0u) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    EXPECT_TRUE(texture_folders(tmp).empty());
  }
}

// A checkerboard of black and white texels (linear data, so that filtering is a plain
// average): a footprint as wide as the texture averages it to grey, a zero one gives a pure
// texel.
TEST(Texture, AWideFootprintAveragesAndAZeroOneGivesAPureTexel) {
  const TempDir dir("texture");
  constexpr int n = 16;
  Image img(n, n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      for (int c = 0; c < 3; ++c) img.row(y)[3 * x + c] = float((x + y) % 2);
  const std::string path = dir.path("checker.png");
  write_image(path, img);
  const TextureSet set({TextureDesc{path, {}, false}});
  for (const float u : {0.3f, 0.5f, 0.71f}) {
    const vec4 wide = set.sample(0, u, 0.4f, 1.0f);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(wide[c], 0.5f, 0.05f) << "u " << u;
  }
  for (int x = 0; x < 3; ++x) {
    const float u = (float(x) + 0.5f) / n, v = 1.0f - 0.5f / n;  // row 0
    const vec4 sharp = set.sample(0, u, v, 0.0f);
    EXPECT_NEAR(sharp[0], float(x % 2), 1e-4f) << x;
  }
}

// Opening reads every texel and makes every mip level: lookups anywhere, with footprints
// from none to the whole image, then make no tile (so the first frame costs what the others
// do). A 256 x 256 PNG has no mip levels of its own: OIIO makes 8.
TEST(Texture, LookupsAfterOpeningMakeNoTile) {
  const TempDir dir("texture");
  constexpr int n = 256;
  Image img(n, n);
  for (std::size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = float((i * 7919) % 256) / 255.0f;
  const std::string path = dir.path("noise.png");
  write_image(path, img);
  const TextureSet set({TextureDesc{path, {}, true}});
  const long long made = set.tiles_made();
  EXPECT_GT(made, 0);
  for (float width = 0.0f; width <= 1.0f; width = width == 0.0f ? 0.5f / n : 2.0f * width)
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) (void)set.sample(0, (float(x) + 0.3f) / 16.0f, (float(y) + 0.6f) / 16.0f, width);
  EXPECT_EQ(set.tiles_made(), made);
}

// Under ASan each band of 64 rows OIIO 2.4's texture cache reads from a file costs a 64 MiB
// allocation that ASan poisons: the tall texture is shorter there.
#if defined(__SANITIZE_ADDRESS__)
constexpr int kTall = 2000;
#else
constexpr int kTall = 100000;
#endif

// Images one texel wide or tall, 1 x 1, and 100,000 texels long give their texels at the
// texel centres (within 1 %: a float v near 1 is a hundredth of a texel of 100,000 apart).
TEST(Texture, ThinWideAndTallImagesGiveTheirTexels) {
  const TempDir dir("texture");
  const auto colour = [](int i) {
    return std::array<float, 3>{float(i % 5) / 4.0f, float(i % 3) / 2.0f, float(i % 2)};
  };
  for (const auto& [w, h] : {std::pair{1, 1}, std::pair{1, 7}, std::pair{7, 1},
                             std::pair{1, kTall}, std::pair{100000, 1}}) {
    SCOPED_TRACE(std::to_string(w) + " x " + std::to_string(h));
    Image img(w, h);
    for (int i = 0; i < w * h; ++i)  // written sRGB-encoded: colour(i), to 8 bits
      for (int c = 0; c < 3; ++c)
        img.rgb[std::size_t(3 * i + c)] = srgb_decode(colour(i)[std::size_t(c)]);
    const std::string path = dir.path("thin.png");
    write_image(path, img);
    const TextureSet set({TextureDesc{path, {}, true}});
    const int n = w * h;
    for (const int i : {0, 1, 2, 3, 4, 6, n / 2 + 1, n - 2, n - 1}) {
      if (i < 0 || i >= n) continue;
      const int x = w == 1 ? 0 : i, y = w == 1 ? i : 0;
      const float u = (float(x) + 0.5f) / float(w), v = 1.0f - (float(y) + 0.5f) / float(h);
      const vec4 got = set.sample(0, u, v, 0.0f);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(got[c], srgb_decode(colour(i)[std::size_t(c)]), 0.01f) << "texel " << i;
    }
  }
}

}  // namespace
}  // namespace rt2
