// rt2cpr and the files it reads and writes: success only when the bytes are on disk, no
// output that overwrites an input, the reference checked before the first frame, display
// images in sRGB, line-buffered progress, and the command line a user expects (--version,
// a positional scene, defaults in --help).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <thread>

#include "rt2/image/image_compare.h"
#include "rt2/image/image_io.h"
#include "rt2/image/srgb.h"
#include "tests/rt2cpr/cli_fixture.h"
#include "tests/rt2/small_file_system.h"

namespace {

using rt2::test::Cli;
using rt2::test::kTiny;
using rt2::test::Outcome;
namespace fs = std::filesystem;

TEST_F(Cli, AFullDiskFailsEveryImageFormatWithOneLineAndLeavesNoFile) {
  const rt2::test::SmallFileSystem disk;
  if (!disk.available()) GTEST_SKIP() << disk.why_not();
  for (const char* ext : {"png", "jpg", "exr", "ppm", "tif", "hdr"}) {
    const std::string out = disk.path(std::string("x.") + ext);
    const Outcome r = run("--width 400 --height 300 --subpixels 4 --quiet --output " + out);
    expect_clean_failure(r, "rt2cpr: cannot write " + out + ": No space left on device");
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(disk.entries(), 0u) << ext;
  }
}

TEST_F(Cli, StatsToDevFullFailsInsteadOfReportingSuccess) {
  fs::create_symlink("/dev/full", path("s.json"));
  const Outcome r = run(std::string(kTiny) + " --stats " + path("s.json"));
  expect_clean_failure(r, "cannot write " + path("s.json") + ": No space left on device");
  EXPECT_EQ(r.out.find("wrote"), std::string::npos);
}

TEST_F(Cli, StatsMustBeJsonAndNeverAnInputOrTheImage) {
  write("scene.toml", "[camera]\nposition = [0, 1, 6]\nlook_at = [0, 0, 0]\n");
  const std::string scene_text = slurp(path("scene.toml"));
  expect_clean_failure(run("--stats " + path("scene.toml") + " " + path("scene.toml")), ".json");
  expect_clean_failure(run("--stats " + path("out.png") + " --output " + path("out.png")), ".json");
  fs::create_symlink("scene.toml", path("scene.json"));  // a .json name for the scene itself
  expect_clean_failure(run("--scene " + path("scene.toml") + " --stats " + path("scene.json")),
                       "same file as --scene");
  expect_clean_failure(run("--reference " + path("r.json") + " --stats " + path("./r.json")),
                       "same file as --reference");
  expect_clean_failure(run("--reference " + path("r.png") + " --output " + path("r.png")),
                       "same file as --reference");
  EXPECT_EQ(slurp(path("scene.toml")), scene_text);
  EXPECT_FALSE(fs::exists(path("out.png")));
}

TEST_F(Cli, EmptyPathsAndADirectoryAsOutputGetAClearError) {
  expect_clean_failure(run("--output ''"), "--output: empty file name");
  expect_clean_failure(run("--stats ''"), "--stats: empty file name");
  expect_clean_failure(run("--scene ''"), "--scene: empty file name");
  fs::create_directory(path("d.png"));
  expect_clean_failure(run(std::string(kTiny) + " --output " + path("d.png")), "is a directory");
}

TEST_F(Cli, AReadOnlyOutputIsRefusedAndASymlinkIsWrittenThrough) {
  write("keep.png", "precious");
  ::chmod(path("keep.png").c_str(), 0444);
  expect_clean_failure(run(std::string(kTiny) + " --output " + path("keep.png")), "is read-only");
  EXPECT_EQ(slurp(path("keep.png")), "precious");
  fs::create_symlink("target.png", path("link.png"));
  ASSERT_EQ(run(std::string(kTiny) + " --output " + path("link.png")).status, 0);
  EXPECT_TRUE(fs::is_symlink(path("link.png")));
  EXPECT_EQ(rt2::read_image(path("target.png")).width, 24);
}

TEST_F(Cli, ABadReferenceFailsBeforeTheFirstFrame) {
  const std::string render = " --width 24 --height 16 --output " + path("o.png");
  for (const auto& [ref, needle] :
       {std::pair{path("typo.exr"), std::string("No such file")},
        {path("text.exr"), std::string("cannot read image")},
        {std::string("/dev/zero"), std::string("not a regular file")},
        {path("fifo.exr"), std::string("not a regular file")},
        {path("small.exr"), std::string("reference image is 8x8, the render is 24x16")}}) {
    if (ref == path("text.exr")) write("text.exr", "not an image\n");
    if (ref == path("fifo.exr")) {
      ASSERT_EQ(::mkfifo(ref.c_str(), 0600), 0);
    }
    if (ref == path("small.exr")) {
      ASSERT_EQ(run("--width 8 --height 8 --quiet --output " + ref).status, 0);
    }
    const Outcome r = run("--reference " + ref + render);
    expect_clean_failure(r, needle);
    EXPECT_EQ(r.out.find("fps"), std::string::npos) << "rendered before failing: " << ref;
    EXPECT_FALSE(fs::exists(path("o.png")));
  }
}

TEST_F(Cli, PngIsTheSrgbEncodingOfTheLinearExr) {
  const std::string args = " --width 64 --height 48 --subpixels 4 --quiet --output ";
  ASSERT_EQ(run(args + path("a.png")).status, 0);
  ASSERT_EQ(run(args + path("a.exr")).status, 0);
  // OpenImageIO's own conversion of the linear EXR is the oracle.
  const std::string cmd = "oiiotool " + path("a.exr") + " --colorconvert linear sRGB -d uint8 -o " +
                          path("b.png") + " 2>" + path("oiiotool.err");
  ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(path("oiiotool.err"));
  // Compare the encoded values (what a viewer shows), read without decoding.
  const rt2::Image a = rt2::read_image(path("a.png")), b = rt2::read_image(path("b.png"));
  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  rt2::Image ea = a, eb = b;
  for (float& v : ea.rgb) v = rt2::srgb_encode(v);
  for (float& v : eb.rgb) v = rt2::srgb_encode(v);
  const double psnr = rt2::compare_images(ea, eb).psnr;
  EXPECT_GE(psnr, 45.0);
  // And the EXR holds linear values: its mean is well below the PNG's encoded mean.
  const rt2::Image exr = rt2::read_image(path("a.exr"));
  double mean_linear = 0, mean_encoded = 0;
  for (std::size_t i = 0; i < exr.rgb.size(); ++i) {
    mean_linear += std::clamp(exr.rgb[i], 0.0f, 1.0f);
    mean_encoded += ea.rgb[i];
  }
  EXPECT_LT(mean_linear, 0.8 * mean_encoded);
}

TEST_F(Cli, ProgressLinesReachAFileAsTheyArePrinted) {
  // stdout is a file here; a killed run must still have left its lines in it.
  const std::string out = path("log.txt");
  const std::string cmd = std::string(rt2::test::kChildEnv) + RT2CPR_BIN +
                          " --width 320 --height 240 --subpixels 16 --frames 100000 >" + out +
                          " 2>/dev/null & echo $!";
  FILE* p = ::popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  int pid = 0;
  ASSERT_EQ(std::fscanf(p, "%d", &pid), 1);
  ::pclose(p);
  bool seen = false;
  for (int i = 0; i < 600 && !seen; ++i) {  // up to 60 s (sanitizer builds are slow)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    seen = slurp(out).find("frame 1:") != std::string::npos;
  }
  ::kill(pid, SIGKILL);
  EXPECT_TRUE(seen) << "the first frame's line did not reach the file";
  EXPECT_NE(slurp(out).find("scene built-in"), std::string::npos);
}

TEST_F(Cli, VersionNamesTheCommitCompilerAndIsaAndStatsCarryThem) {
  const Outcome r = run("--version");
  ASSERT_EQ(r.status, 0);
  EXPECT_EQ(r.out.rfind("rt2 ", 0), 0u) << r.out;
  for (const char* s : {"commit ", "g++", "sse4.1"}) EXPECT_NE(r.out.find(s), std::string::npos) << s;
  ASSERT_EQ(run(std::string(kTiny) + " --stats " + path("s.json")).status, 0);
  const auto j = nlohmann::json::parse(slurp(path("s.json")));
  for (const char* key : {"rt2_version", "git_commit", "compiler", "isa"})
    EXPECT_TRUE(j.contains(key)) << key;
}

TEST_F(Cli, ASceneMayBeGivenAsAPositionalArgument) {
  write("tri.obj", "v -1 0 0\nv 1 0 0\nv 0 1.5 0\nf 1 2 3\n");
  ASSERT_EQ(run(std::string(kTiny) + " " + path("tri.obj") + " --stats " + path("s.json")).status, 0);
  EXPECT_EQ(nlohmann::json::parse(slurp(path("s.json")))["scene"], path("tri.obj"));
  expect_clean_failure(run(path("tri.obj") + " --scene " + path("tri.obj")), "two scenes");
}

TEST_F(Cli, HelpShowsEveryDefaultAndLightsMinusOneIsARangeError) {
  const Outcome h = run("--help");
  for (const char* s : {"--width INT=800", "--height INT=600", "--subpixels INT=1", "--depth INT=4",
                        "--min-weight FLOAT=0.01", "--grain INT=4", "--leaf-size INT=4",
                        "--backend TEXT=omp", "--triangle-test TEXT=fast", "--frames INT=1"})
    EXPECT_NE(h.out.find(s), std::string::npos) << s;
  expect_clean_failure(run("--lights -1"), "lights must be in [0, 1000000], got -1");
  expect_clean_failure(run("--lights -1000"), "lights must be in [0, 1000000], got -1000");
}

#if !defined(__SANITIZE_ADDRESS__)  // ASan reserves terabytes of address space up front
TEST_F(Cli, HelpStartsInASmallAddressSpace) {
  // Image I/O is loaded only when an image is read or written: --help never loads it.
  const std::string cmd = "ulimit -v 100000; " + std::string(RT2CPR_BIN) + " --help >" +
                          path("stdout") + " 2>" + path("stderr");
  EXPECT_EQ(std::system(("sh -c '" + cmd + "'").c_str()), 0) << slurp(path("stderr"));
  EXPECT_NE(slurp(path("stdout")).find("--output"), std::string::npos);
}
#endif

}  // namespace
