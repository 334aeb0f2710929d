// rt2cpr end to end: options, presets, outputs, and every class of bad input failing with
// one line on stderr, a non-zero exit and no output file left behind.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "rt2/image/image_io.h"
#include "tests/rt2cpr/cli_fixture.h"

namespace {

using rt2::test::Cli;
using rt2::test::kTiny;
using rt2::test::Outcome;
namespace fs = std::filesystem;

TEST_F(Cli, HelpListsOptionsAndExamplesAndExitsZero) {
  const Outcome r = run("--help");
  EXPECT_EQ(r.status, 0);
  for (const char* s : {"--preset", "--backend", "--grain", "--leaf-size", "--stats", "Examples"})
    EXPECT_NE(r.out.find(s), std::string::npos) << s;
}

TEST_F(Cli, RendersTheBuiltInSceneToPngWithStatsJson) {
  const Outcome r = run(std::string(kTiny) + " --frames 2 --output " + path("a.png") + " --stats " +
                    path("s.json"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::file_size(path("a.png")) > 0);
  const auto j = nlohmann::json::parse(slurp(path("s.json")));
  for (const char* key : {"fps_median", "fps_min", "fps_max", "mrays_per_s", "rays_primary",
                          "rays_shadow", "rays_reflection", "rays_refraction", "scene_load_ms",
                          "bvh_build_ms", "frame_ms", "backend", "grain", "leaf_size"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["rays_primary"].get<int>(), 24 * 16);
  EXPECT_EQ(j["frame_ms"].size(), 2u);
  EXPECT_EQ(files_other_than_streams(), 2u);  // no temporary files left
}

TEST_F(Cli, PresetSetsTheThesisValuesAndExplicitOptionsOverrideIt) {
  ASSERT_EQ(run("--preset hard --width 30 --height 20 --quiet --stats " + path("s.json")).status, 0);
  const auto j = nlohmann::json::parse(slurp(path("s.json")));
  EXPECT_EQ(j["width"], 30);
  EXPECT_EQ(j["subpixels"], 3);
  EXPECT_EQ(j["depth"], 4);
  EXPECT_EQ(j["lights"], 2);
}

TEST_F(Cli, EveryBackendWritesTheSameImage) {
  for (const char* b : {"serial", "omp", "tbb"})
    ASSERT_EQ(run(std::string(kTiny) + " --backend " + b + " --output " + path(std::string(b) + ".exr")).status, 0);
  // Compare decoded pixels: the files' headers carry a timestamp.
  const rt2::Image serial = rt2::read_image(path("serial.exr"));
  EXPECT_EQ(serial.rgb, rt2::read_image(path("omp.exr")).rgb);
  EXPECT_EQ(serial.rgb, rt2::read_image(path("tbb.exr")).rgb);
}

TEST_F(Cli, MissingSceneFileFailsNamingIt) {
  expect_clean_failure(run("--scene " + path("nope.toml") + " --output " + path("x.png")), "nope.toml");
  EXPECT_FALSE(fs::exists(path("x.png")));
}

TEST_F(Cli, MalformedSceneFileFailsWithFileAndLine) {
  write("bad.toml", "[camera]\nposition = [0, 1, 6]\nlook_at = [0, 1\n");
  expect_clean_failure(run("--scene " + path("bad.toml")), "bad.toml:");
}

TEST_F(Cli, NaNCoordinatesInASceneFail) {
  write("nan.toml",
        "[camera]\nposition = [0, 1, 6]\nlook_at = [0, 1, 0]\n[materials.m]\n"
        "[[spheres]]\ncenter = [nan, 0, 0]\nradius = 1\nmaterial = \"m\"\n");
  expect_clean_failure(run("--scene " + path("nan.toml")), "nan.toml:");
}

TEST_F(Cli, ObjWithIndexOutOfRangeFails) {
  write("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
  expect_clean_failure(run("--scene " + path("bad.obj")), "bad.obj");
}

TEST_F(Cli, AbsurdParametersFailBeforeRendering) {
  expect_clean_failure(run("--width -4"), "width");
  expect_clean_failure(run("--subpixels 0"), "subpixels");
  expect_clean_failure(run("--depth -1"), "depth");
  expect_clean_failure(run("--min-weight nan"), "min-weight");
  expect_clean_failure(run("--threads -2"), "threads");
  expect_clean_failure(run("--grain 0"), "grain");
  expect_clean_failure(run("--frames 0"), "frames");
  expect_clean_failure(run("--leaf-size 0"), "leaf-size");
  expect_clean_failure(run("--width abc"), "width");
  expect_clean_failure(run("--no-such-option"), "no-such-option");
}

TEST_F(Cli, UnknownBackendPresetPatternSplitAndIsaFail) {
  expect_clean_failure(run("--backend cuda"), "cuda");
  expect_clean_failure(run("--preset ultra"), "ultra");
  expect_clean_failure(run("--pattern hexagon"), "hexagon");
  expect_clean_failure(run("--split median"), "median");
  expect_clean_failure(run("--isa avx9000"), "avx9000");
}

TEST_F(Cli, ImageLargerThanMemoryFailsBeforeAllocating) {
  expect_clean_failure(run("--width 65535 --height 65535 --output " + path("huge.exr")), "GiB");
  EXPECT_FALSE(fs::exists(path("huge.exr")));
}

TEST_F(Cli, UnwritableOrUnsupportedOutputFailsAndLeavesNoFile) {
  expect_clean_failure(run(std::string(kTiny) + " --output " + path("missing/dir/x.png")), "does not exist");
  expect_clean_failure(run(std::string(kTiny) + " --output " + path("x.xyz")), "unsupported");
  expect_clean_failure(run(std::string(kTiny) + " --stats " + path("missing/s.json")), "does not exist");
  EXPECT_EQ(files_other_than_streams(), 0u);
}

TEST_F(Cli, ReferenceComparisonIsPrintedAndWrittenToStats) {
  ASSERT_EQ(run(std::string(kTiny) + " --subpixels 16 --output " + path("ref.exr")).status, 0);
  const Outcome same = run(std::string(kTiny) + " --subpixels 16 --reference " + path("ref.exr") +
                           " --stats " + path("same.json"));
  ASSERT_EQ(same.status, 0) << same.err;
  const auto j = nlohmann::json::parse(slurp(path("same.json")));
  EXPECT_EQ(j["reference"]["rmse"].get<double>(), 0.0);
  EXPECT_TRUE(j["reference"]["psnr"].is_null());  // +inf has no JSON form
  ASSERT_EQ(run(std::string(kTiny) + " --reference " + path("ref.exr") + " --stats " + path("one.json")).status, 0);
  const auto k = nlohmann::json::parse(slurp(path("one.json")));
  EXPECT_GT(k["reference"]["rmse"].get<double>(), 0.0);
  EXPECT_GT(k["reference"]["edge_pixels"].get<int>(), 0);
  EXPECT_GT(k["reference"]["edge_rmse"].get<double>(), 0.0);  // 1 sample against 16 differs
  expect_clean_failure(run("--width 10 --height 10 --quiet --reference " + path("ref.exr")), "reference image is 24x16");
}

TEST_F(Cli, PassesTilesAndBlocksGiveTheImageOfOnePass) {
  const std::string base = std::string(kTiny) + " --subpixels 4 --depth 6 ";
  ASSERT_EQ(run(base + "--output " + path("one.exr")).status, 0);
  ASSERT_EQ(run(base + "--passes 4 --tile 5 --block 3 --output " + path("four.exr")).status, 0);
  EXPECT_EQ(rt2::read_image(path("one.exr")).rgb, rt2::read_image(path("four.exr")).rgb);
  expect_clean_failure(run(base + "--passes 5"), "passes must be in [1, subpixels = 4]");
  expect_clean_failure(run(base + "--tile -1"), "tile");
  expect_clean_failure(run(base + "--block 0"), "block");
  expect_clean_failure(run(base + "--time-budget -1"), "time-budget");
}

TEST_F(Cli, ATimeBudgetStopsAfterTheLastPassThatFitsAndStillWritesTheImage) {
  const Outcome r = run("--width 64 --height 48 --quiet --subpixels 16 --passes 16 "
                        "--time-budget 0.000001 --output " + path("quick.png") + " --stats " +
                        path("s.json"));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(path("s.json")));
  EXPECT_EQ(j["passes"], 16);
  EXPECT_EQ(j["passes_rendered"], 1);  // the first pass always runs
  EXPECT_EQ(j["rays_primary"], 64 * 48);
  EXPECT_EQ(rt2::read_image(path("quick.png")).width, 64);
}

TEST_F(Cli, StatsCountTheBvhWalkOfEachKindOfRay) {
  ASSERT_EQ(run(std::string(kTiny) + " --stats " + path("s.json")).status, 0);
  const auto j = nlohmann::json::parse(slurp(path("s.json")));
  for (const char* kind : {"primary", "shadow", "secondary"}) {
    ASSERT_TRUE(j["bvh_walks"].contains(kind)) << kind;
    EXPECT_GT(j["bvh_walks"][kind]["nodes"].get<std::uint64_t>(), 0u) << kind;
  }
}

// Many lights: every culling mode writes the image of none; moving lights are rebuilt each
// frame and the stats say what it cost; bad values fail with one line.
TEST_F(Cli, LightCullingModesWriteTheSameImageAndStatsCountLightsAndUpdates) {
  const std::string base = std::string(kTiny) + " --lights 300 --light-range 0.3,0.8 ";
  ASSERT_EQ(run(base + "--light-culling none --output " + path("none.exr")).status, 0);
  for (const char* mode : {"tiled --light-lists brute-force", "clustered --light-slices 3", "bvh"}) {
    const Outcome r = run(base + "--light-culling " + mode + " --output " + path("m.exr"));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(rt2::read_image(path("none.exr")).rgb, rt2::read_image(path("m.exr")).rgb) << mode;
  }
  const Outcome r = run(base + "--light-culling clustered --animate-lights --stage-times --frames 3 "
                        "--stats " + path("s.json"));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(path("s.json")));
  EXPECT_EQ(j["lights"], 300);
  EXPECT_EQ(j["lights_with_range"], 299);  // the scene's own light has none
  EXPECT_EQ(j["light_culling"], "clustered");
  EXPECT_GT(j["light_counts"]["lists"].get<std::uint64_t>(), 0u);
  EXPECT_GE(j["light_counts"]["considered"].get<std::uint64_t>(),
            j["light_counts"]["in_range"].get<std::uint64_t>());
  for (const char* step : {"lights", "morton", "sort", "tree", "total"})
    EXPECT_TRUE(j["light_update_ms"].contains(step)) << step;
  for (const char* stage : {"generate", "intersect", "lights", "shade", "shadow"})
    EXPECT_TRUE(j["stage_ms"].contains(stage)) << stage;
  expect_clean_failure(run("--light-culling octree"), "octree");
  expect_clean_failure(run("--light-lists magic"), "magic");
  expect_clean_failure(run("--light-slices 0"), "light slices");
  expect_clean_failure(run("--light-range 0"), "light-range");
  expect_clean_failure(run("--light-range 2,1"), "light-range");
  expect_clean_failure(run("--light-range 1,x"), "light-range");
  expect_clean_failure(run("--light-range nan"), "light-range");
  expect_clean_failure(run("--shadows maybe"), "maybe");
  expect_clean_failure(run(std::string(kTiny) + " --light-range 5"), "no lights are added");
}

TEST_F(Cli, AnObjAloneIsFramedAndRendered) {
  write("tri.obj", "v -1 0 0\nv 1 0 0\nv 0 1.5 0\nv 0 0.5 1\nf 1 2 3\nf 1 2 4\nf 2 3 4\nf 3 1 4\n");
  const Outcome r = run(std::string(kTiny) + " --scene " + path("tri.obj") + " --output " + path("t.png"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(path("t.png")));
}

TEST_F(Cli, BadToneCurveOrExposureFailsNamingTheOption) {
  expect_clean_failure(run(std::string(kTiny) + " --tonemap bogus --output " + path("x.png")), "--tonemap");
  expect_clean_failure(run(std::string(kTiny) + " --exposure 100 --output " + path("x.png")), "exposure");
  expect_clean_failure(run(std::string(kTiny) + " --exposure nan"), "exposure");
  EXPECT_EQ(files_other_than_streams(), 0u);
}

// The tone curve changes display formats only: an EXR keeps the linear values.
TEST_F(Cli, ToneMappedRendersWritePngAndExrAndOnlyThePngChanges) {
  for (const char* curve : {"none", "aces"})
    for (const char* ext : {".png", ".exr"}) {
      const std::string out = path(std::string(curve) + ext);
      const Outcome r = run(std::string(kTiny) + " --tonemap " + curve + " --exposure 1 --output " + out);
      ASSERT_EQ(r.status, 0) << curve << ext << ": " << r.err;
      ASSERT_TRUE(fs::exists(out)) << out;
    }
  EXPECT_EQ(rt2::read_image(path("none.exr")).rgb, rt2::read_image(path("aces.exr")).rgb);
  EXPECT_NE(rt2::read_image(path("none.png")).rgb, rt2::read_image(path("aces.png")).rgb);
}

TEST_F(Cli, AMissingEnvironmentImageFailsNamingItAndWritesNothing) {
  const Outcome r = run(std::string(kTiny) + " --environment " + path("missing.hdr") + " --output " +
                        path("x.exr") + " --stats " + path("s.json"));
  expect_clean_failure(r, path("missing.hdr"));
  EXPECT_EQ(files_other_than_streams(), 0u);
}

// A sphere in the middle of the view: the corners see the background, black without an
// environment and the sky's light with --environment sky.
TEST_F(Cli, EnvironmentSkyLightsTheBackground) {
  write("ball.toml",
        "[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\n[materials.m]\n"
        "[[spheres]]\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"m\"\n"
        "[[lights]]\nposition = [2, 3, 4]\n");
  const std::string base = std::string(kTiny) + " --scene " + path("ball.toml") + " --output ";
  const Outcome sky = run(base + path("sky.exr") + " --environment sky");
  ASSERT_EQ(sky.status, 0) << sky.err;
  ASSERT_EQ(run(base + path("black.exr")).status, 0);
  const rt2::Image lit = rt2::read_image(path("sky.exr")), dark = rt2::read_image(path("black.exr"));
  for (const auto& [x, y] : {std::pair{0, 0}, std::pair{23, 0}, std::pair{0, 15}, std::pair{23, 15}})
    for (int c = 0; c < 3; ++c) {
      EXPECT_GT(lit.pixel(x, y)[c], 0.0f) << x << "," << y;
      EXPECT_EQ(dark.pixel(x, y)[c], 0.0f) << x << "," << y;
    }
  // and the built-in scene renders with it
  const Outcome builtin = run(std::string(kTiny) + " --environment sky --output " + path("b.png"));
  ASSERT_EQ(builtin.status, 0) << builtin.err;
}

// tinyobjloader kept every material of an MTL library, some 2 KB each: 2.3 GB of memory for
// a million of them. rt2 keeps those that faces use. The peak is that of the rt2cpr process.
TEST_F(Cli, AMillionMaterialMtlTakesLittleMemory) {
  std::string mtl;
  for (int i = 0; i < 1000000; ++i) mtl += "newmtl m" + std::to_string(i) + "\nKd 0.5\nNs 10\n";
  write("many.mtl", mtl);
  write("many.obj", "mtllib many.mtl\nusemtl m999999\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const std::string scene = path("many.obj");
    execl(RT2CPR_BIN, RT2CPR_BIN, "--scene", scene.c_str(), "--width", "8", "--height", "8",
          "--quiet", static_cast<char*>(nullptr));
    _exit(127);
  }
  int status = 0;
  rusage usage{};
  ASSERT_EQ(wait4(pid, &status, 0, &usage), pid);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "status " << status;
  const double mib = double(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB
  std::printf("[ measure  ] peak memory with a %.0f MiB MTL of 1,000,000 materials: %.0f MiB\n",
              double(mtl.size()) / (1 << 20), mib);
#if defined(__SANITIZE_ADDRESS__)
  EXPECT_LT(mib, 1024.0);  // AddressSanitizer's shadow memory and quarantine
#else
  EXPECT_LT(mib, 400.0);
#endif
}

}  // namespace

// --camera: a file holding only a [camera] table replaces the scene's camera. The glass
// scene rendered with its own camera's table as --camera is the same bits as without it,
// and another camera gives another image.
TEST_F(Cli, CameraFileReplacesTheScenesCamera) {
  const std::string glass = std::string(RT2_SOURCE_DIR) + "/scenes/glass.toml";
  ASSERT_EQ(run(std::string(kTiny) + " --scene " + glass + " --output " + path("own.exr")).status, 0);
  // The glass scene's [camera] table, copied out of the file.
  std::istringstream in(slurp(glass));
  std::string line, table;
  bool inside = false;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] == '[') inside = line.rfind("[camera]", 0) == 0;
    if (inside) table += line + "\n";
  }
  ASSERT_NE(table.find("position"), std::string::npos);
  write("cam.toml", table);
  const Outcome r = run(std::string(kTiny) + " --scene " + glass + " --camera " + path("cam.toml") +
                        " --output " + path("given.exr"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(rt2::read_image(path("own.exr")).rgb, rt2::read_image(path("given.exr")).rgb);
  write("other.toml", "[camera]\nposition = [0, 2, 6]\ndirection = [0, -0.3, -1]\nfov = 50\n");
  ASSERT_EQ(run(std::string(kTiny) + " --scene " + glass + " --camera " + path("other.toml") +
                " --output " + path("other.exr")).status, 0);
  EXPECT_NE(rt2::read_image(path("own.exr")).rgb, rt2::read_image(path("other.exr")).rgb);
}

TEST_F(Cli, CameraFileWithMoreThanACameraOrABadOneFailsWithItsLine) {
  write("scene.toml", "[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\n[world]\nambient = [0, 0, 0]\n");
  expect_clean_failure(run(std::string(kTiny) + " --camera " + path("scene.toml") + " --output " + path("x.png")),
                       "scene.toml:4");
  write("nan.toml", "[camera]\nposition = [0, nan, 5]\nlook_at = [0, 0, 0]\n");
  expect_clean_failure(run(std::string(kTiny) + " --camera " + path("nan.toml") + " --output " + path("x.png")),
                       "nan.toml:2");
  expect_clean_failure(run(std::string(kTiny) + " --camera " + path("missing.toml")), "missing.toml");
  expect_clean_failure(run(std::string(kTiny) + " --camera " + path("x.png") + " --output " + path("x.png")),
                       "same file");
  EXPECT_FALSE(fs::exists(path("x.png")));
}

// The viewer's options need --interactive, and the file render's options that mean nothing
// in a window are refused with it: one line each, exit 2.
TEST_F(Cli, ViewerOptionsNeedInteractiveAndFileOptionsAreRefusedWithIt) {
  for (const char* args : {"--script s.txt", "--target-fps 20", "--frame-log f.csv", "--screenshot-key P"}) {
    const Outcome r = run(std::string(kTiny) + " " + args);
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_NE(r.err.find("needs --interactive"), std::string::npos) << r.err;
  }
  for (const char* args : {"--frames 3", "--stats s.json", "--time-budget 1", "--passes 1", "--animate-lights"}) {
    const Outcome r = run(std::string(kTiny) + " --interactive " + args);
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_NE(r.err.find("does not apply to --interactive"), std::string::npos) << r.err;
  }
  expect_clean_failure(run("--interactive --target-fps -1"), "target-fps");
  expect_clean_failure(run("--interactive --frame-log " + path("log.txt")), "must end in .csv");
}

// ---- the command line in rt2cpr's words -------------------------------------------------

namespace {

// CLI11's own wording, from each error class its parser raises (ArgumentMismatch,
// ConversionError, ValidationError, ExtrasError, RequiredError, RequiresError,
// ExcludesError, InvalidError, HorribleError): none of it may reach the user.
const char* const kCli11Phrases[] = {
    "At Most", "At least", "required", "Expected exactly", "Expected at least",
    "Could not convert", "is not an allowed value", "Should be true/false", "too many inputs",
    "flag override", "not expected", "excludes", "requires", "Too many positional",
    "should not see this"};

// `s` in single quotes for the shell, which keeps newlines, tabs and ESC as they are.
std::string sh(const std::string& s) { return "'" + s + "'"; }

class CliWords : public Cli {
 protected:
  // A bad command line: status 2, one line "rt2cpr: ..." in rt2cpr's words. Returns the
  // message after "rt2cpr: ".
  std::string usage_error(const std::string& args) const {
    const Outcome r = run(args);
    EXPECT_EQ(r.status, 2) << args << ": " << r.err;
    EXPECT_EQ(r.err.rfind("rt2cpr: ", 0), 0u) << args << ": " << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << args << ": not one line: " << r.err;
    for (const char* phrase : kCli11Phrases)
      EXPECT_EQ(r.err.find(phrase), std::string::npos) << args << ": CLI11's words: " << r.err;
    if (r.err.size() < 9) return r.err;
    return r.err.substr(8, r.err.size() - 9);
  }
  // The statistics of a quiet render with `args` (its size, or a tiny image).
  nlohmann::json stats_of(const std::string& args) const {
    const std::string size = args.find("--width") == std::string::npos ? kTiny : "--quiet";
    const Outcome r = run(size + " " + args + " --stats " + path("s.json"));
    EXPECT_EQ(r.status, 0) << args << ": " << r.err;
    return nlohmann::json::parse(slurp(path("s.json")));
  }
};

// CLI11's ArgumentMismatch ("At Most 1 required but received 2").
TEST_F(CliWords, AnOptionGivenTwoValuesSaysItTakesOne) {
  EXPECT_EQ(usage_error("--width 5 --width 6"), "--width takes one value, got 2 (\"5 6\")");
  EXPECT_EQ(usage_error("--width 5 6"), "--width takes one value, got 2 (\"5 6\")");
  EXPECT_EQ(usage_error("--scene a.toml --scene=b.toml"),
            "--scene takes one value, got 2 (\"a.toml b.toml\")");
}

// CLI11's ArgumentMismatch ("1 required INT missing").
TEST_F(CliWords, AValueOptionWithoutAValueSaysWhatItNeeds) {
  EXPECT_EQ(usage_error("--width"), "--width needs a value (an integer)");
  EXPECT_EQ(usage_error("--quiet --min-weight"), "--min-weight needs a value (a number)");
  EXPECT_EQ(usage_error("--output"), "--output needs a value (a file)");
  EXPECT_EQ(usage_error("--backend"), "--backend needs a value (a name)");
}

// CLI11's ConversionError ("Could not convert: --width = abc"); CLI11 also read "010" as
// eight, "0x10" as sixteen and "" as zero.
TEST_F(CliWords, ANumberThatIsNotOneIsNamedWithItsOption) {
  EXPECT_EQ(usage_error("--width abc"), "--width needs an integer, got \"abc\"");
  EXPECT_EQ(usage_error("--width 1.5"), "--width needs an integer, got \"1.5\"");
  EXPECT_EQ(usage_error("--width ''"), "--width needs an integer, got \"\"");
  EXPECT_EQ(usage_error("--frames 0x10"), "--frames needs an integer, got \"0x10\"");
  EXPECT_EQ(usage_error("--width 99999999999"),
            "--width needs an integer from -2147483648 to 2147483647, got \"99999999999\"");
  EXPECT_EQ(usage_error("--leaf-size 0"),
            "--leaf-size needs an integer from 1 to 4294967295, got \"0\"");
  EXPECT_EQ(usage_error("--min-weight abc"), "--min-weight needs a number, got \"abc\"");
  EXPECT_EQ(usage_error("--exposure 0x1p3"), "--exposure needs a number, got \"0x1p3\"");
  EXPECT_EQ(stats_of("--width 010 --height 8")["width"], 10);  // not eight
}

// CLI11's ConversionError for flags ("--quiet: Should be true/false or a number"); CLI11
// took --quiet=yes silently.
TEST_F(CliWords, AFlagGivenAValueSaysItTakesNone) {
  EXPECT_EQ(usage_error("--quiet=yes"), "--quiet takes no value, got \"yes\"");
  EXPECT_EQ(usage_error("--no-bvh 1"), "--no-bvh takes no value, got \"1\"");
}

// CLI11's ExtrasError ("The following argument was not expected: b.toml").
TEST_F(CliWords, ExtraArgumentsAreRefusedInRt2sWords) {
  EXPECT_EQ(usage_error("a.toml b.toml"), "two scenes given: \"a.toml\" and \"b.toml\"");
  EXPECT_EQ(usage_error("a.toml -- b.toml"), "two scenes given: \"a.toml\" and \"b.toml\"");
  EXPECT_EQ(usage_error("-x"), "unknown option -x (see --help)");
  EXPECT_EQ(usage_error("--frobnicate=3"), "unknown option --frobnicate (see --help)");
}

// Every kind of bad command line, CLI11's RequiredError, ExcludesError, RequiresError and
// ValidationError included (rt2cpr declares no required, excluding or validated option, so
// CLI11 has nothing to raise them for): each one line, status 2, in rt2cpr's words.
TEST_F(CliWords, NoCli11WordingReachesTheUser) {
  for (const char* args :
       {"--width 5 --width 6", "--width", "--width x", "--quiet=2", "--quiet=", "a b c",
        "--scene", "--scene --width 5", "--help-all", "--version=1", "- -", "--=x", "-1 -2",
        "--interactive=no", "--lights 1 2 3", "--light-range", "--preset", "--stats",
        "--max-texture-pixels", "--allow-outside-assets 2", "--rank0", "--threads -"})
    usage_error(args);
}

TEST_F(CliWords, AMisspeltOptionGetsTheClosestKnownOne) {
  EXPECT_EQ(usage_error("--subpixel 4"), "unknown option --subpixel; did you mean --subpixels?");
  EXPECT_EQ(usage_error("--subpixel=4"), "unknown option --subpixel; did you mean --subpixels?");
  EXPECT_EQ(usage_error("--widht 5"), "unknown option --widht; did you mean --width?");
  EXPECT_EQ(usage_error("--Depth 5"), "unknown option --Depth; did you mean --depth?");
  EXPECT_EQ(usage_error("--leaf 8"), "unknown option --leaf; did you mean --leaf-size?");
  EXPECT_EQ(usage_error("--light-culing bvh"),
            "unknown option --light-culing; did you mean --light-culling?");
  EXPECT_EQ(usage_error("--zebra 3"), "unknown option --zebra (see --help)");
}

TEST_F(CliWords, PositionalJunkThatLooksLikeAnOptionGetsASuggestion) {
  EXPECT_EQ(usage_error("-subpixels 4"), "unknown option -subpixels; did you mean --subpixels?");
  EXPECT_EQ(usage_error("---depth 2"), "unknown option ---depth; did you mean --depth?");
  EXPECT_EQ(usage_error("\xE2\x80\x94subpixels 4"),  // an em dash, as a word processor writes "--"
            "unknown option \xE2\x80\x94subpixels; did you mean --subpixels?");
  EXPECT_EQ(usage_error("subpixels 4"),
            "unexpected argument \"subpixels\"; did you mean --subpixels?");
  EXPECT_EQ(usage_error("width=4"), "unexpected argument \"width=4\"; did you mean --width?");
}

TEST_F(CliWords, AValueOptionNeverTakesTheNextOptionAsItsValue) {
  EXPECT_EQ(usage_error("--scene --width 5"),
            "--scene needs a value (a file), got the option --width");
  EXPECT_EQ(usage_error("--scene=--width=5"),
            "--scene needs a value (a file), got the option --width");
  EXPECT_EQ(usage_error("--output -h"), "--output needs a value (a file), got the option -h");
  EXPECT_EQ(usage_error("--output --out.png"),
            "--output needs a value (a file), got \"--out.png\" (a value may not start with --)");
}

// Every option --help lists with a value, followed by another option: eight runs at a time.
TEST_F(CliWords, EveryValueOptionRefusesAnOptionAsItsValue) {
  std::istringstream lines(run("--help").out);
  std::vector<std::string> names;
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::string name, type;
    if (words >> name >> type && name.rfind("--", 0) == 0 && type.rfind("--", 0) != 0 &&
        std::isupper(static_cast<unsigned char>(type[0])))
      names.push_back(name);
  }
  EXPECT_GE(names.size(), 40u);
  std::string script;
  for (std::size_t i = 0; i < names.size(); ++i)
    script += "(" + std::string(rt2::test::kChildEnv) + RT2CPR_BIN + " " + names[i] +
              " --quiet >/dev/null 2>" + path("err" + std::to_string(i)) + "; echo $? >" +
              path("rc" + std::to_string(i)) + ") & " + (i % 8 == 7 ? "wait; " : "");
  ASSERT_EQ(std::system((script + "wait").c_str()), 0);
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string err = slurp(path("err" + std::to_string(i)));
    EXPECT_EQ(slurp(path("rc" + std::to_string(i))), "2\n") << names[i] << ": " << err;
    EXPECT_EQ(err.rfind("rt2cpr: " + names[i] + " needs a value (", 0), 0u) << err;
    EXPECT_NE(err.find("), got the option --quiet\n"), std::string::npos) << err;
  }
}

TEST_F(CliWords, NegativeNumbersAreValues) {
  EXPECT_EQ(stats_of("--exposure -1")["exposure"], -1.0);
  EXPECT_EQ(stats_of("--exposure=-1.5")["exposure"], -1.5);
  EXPECT_EQ(stats_of("--min-weight -0 --exposure -.5")["exposure"], -0.5);
}

// OpenImageIO's reason named "image.pgn", a file of its own making.
TEST_F(CliWords, AnUnknownOutputFormatNamesTheUsersPath) {
  for (const std::string& args : {std::string(kTiny) + " --output " + path("a.pgn"),
                                  "--interactive --output " + path("a.pgn")}) {
    const std::string message = usage_error(args);
    EXPECT_EQ(message.rfind("--output " + path("a.pgn") + ": unsupported image format '.pgn'", 0),
              0u) << message;
    EXPECT_EQ(message.find("image.pgn"), std::string::npos) << message;
  }
  const std::string no_extension = usage_error("--output " + path("a"));
  EXPECT_EQ(no_extension.rfind("--output " + path("a") + ": no extension", 0), 0u) << no_extension;
  EXPECT_EQ(files_other_than_streams(), 0u);
}

TEST_F(CliWords, EveryOutputPathErrorNamesTheUsersPath) {
  const std::string missing = path("missing") + "/";
  for (const auto& [args, named] :
       {std::pair{"--output " + missing + "x.png", missing + "x.png"},
        {"--stats " + missing + "s.json", missing + "s.json"},
        {"--stats " + path("s.txt"), path("s.txt")},
        {"--output " + path("x.exr") + " --stats " + path("x.exr"), path("x.exr")}}) {
    const Outcome r = run(std::string(kTiny) + " " + args);
    expect_clean_failure(r, named);
  }
  for (const auto& [args, named] :
       {std::pair{"--frame-log " + missing + "f.csv", missing + "f.csv"},
        {"--frame-log " + path("f.txt"), path("f.txt")}}) {
    const Outcome r =
        run_command("DISPLAY=:0 " + std::string(RT2CPR_BIN) + " --interactive " + args);
    if (r.err.find("built without the viewer") != std::string::npos) GTEST_SKIP() << r.err;
    expect_clean_failure(r, named);
  }
  EXPECT_EQ(files_other_than_streams(), 0u);
}

TEST_F(CliWords, AssetOptionsAreDocumentedAndReachTheStats) {
  const Outcome help = run("--help");
  EXPECT_NE(help.out.find("--allow-outside-assets"), std::string::npos);
  EXPECT_NE(help.out.find("--max-texture-pixels INT=268435456"), std::string::npos);
  const auto defaults = stats_of("");
  EXPECT_EQ(defaults["allow_outside_assets"], false);
  EXPECT_EQ(defaults["max_texture_pixels"], 268435456u);
  const auto given = stats_of("--allow-outside-assets --max-texture-pixels 18446744073709551615");
  EXPECT_EQ(given["allow_outside_assets"], true);
  EXPECT_EQ(given["max_texture_pixels"].get<std::uint64_t>(), 18446744073709551615u);
}

TEST_F(CliWords, MaxTexturePixelsIsAPositiveIntegerThatFits) {
  const std::string range = "--max-texture-pixels needs an integer from 1 to 18446744073709551615";
  EXPECT_EQ(usage_error("--max-texture-pixels 0"), range + ", got \"0\"");
  EXPECT_EQ(usage_error("--max-texture-pixels -1"), range + ", got \"-1\"");
  EXPECT_EQ(usage_error("--max-texture-pixels 18446744073709551616"),
            range + ", got \"18446744073709551616\"");
  EXPECT_EQ(usage_error("--max-texture-pixels 1e9"),
            "--max-texture-pixels needs an integer, got \"1e9\"");
  EXPECT_EQ(usage_error("--max-texture-pixels ' 5'"),
            "--max-texture-pixels needs an integer, got \" 5\"");
  EXPECT_EQ(usage_error("--allow-outside-assets=yes"),
            "--allow-outside-assets takes no value, got \"yes\"");
}

// The film of 3000 x 3000 pixels takes 324 MB; the data segment is capped at 200 MB, which
// the program and the built-in scene fit in (no output: the image codec is not loaded).
// Under AddressSanitizer a failed allocation ends the process instead of throwing.
TEST_F(CliWords, OutOfMemoryIsOneLineAndStatusOne) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer cannot run under a data segment cap";
#endif
  const Outcome r = run_command("prlimit --data=" + std::to_string(200 << 20) + " " +
                                RT2CPR_BIN + " --width 3000 --height 3000 --depth 0 --quiet");
  expect_clean_failure(r, "rt2cpr: out of memory while ");
  EXPECT_EQ(r.status, 1);
}

// JSON text is UTF-8: a path that is not (here the scene's) made the statistics fail with
// nlohmann's "invalid UTF-8 byte" after the render.
TEST_F(CliWords, StatsOfASceneWhosePathIsNotUtf8AreWritten) {
  write("bad\xff.obj", "v -1 0 0\nv 1 0 0\nv 0 1.5 0\nf 1 2 3\n");
  const Outcome r = run(std::string(kTiny) + " " + sh(path("bad\xff.obj")) + " --stats " +
                        path("s.json"));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(path("s.json")));
  EXPECT_EQ(j["scene"], path("bad\xEF\xBF\xBD.obj"));  // U+FFFD in place of the bad byte
}

// A newline, a tab or an ESC in a path: every line rt2cpr prints stays one line, its
// control characters escaped (or, in rt2's loader messages and warnings, made blanks).
TEST_F(CliWords, ControlCharactersInMessagesAreEscaped) {
  const auto one_line_without_controls = [](const Outcome& r) {
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
    for (const char c : r.err.substr(0, r.err.size() - 1))
      EXPECT_FALSE(static_cast<unsigned char>(c) < 0x20 || c == 0x7f) << r.err;
  };
  // A scene that does not exist.
  const Outcome missing = run(std::string(kTiny) + " --scene " + sh(path("no\nsuch.toml")));
  EXPECT_EQ(missing.status, 1);
  one_line_without_controls(missing);
  EXPECT_NE(missing.err.find("such.toml"), std::string::npos) << missing.err;
  // A scene that exists renders, and its path is one line in what is printed.
  const std::string scene = path("new\nline.toml");
  write("new\nline.toml", "[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\n[materials.m]\n"
                          "[[spheres]]\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"m\"\n");
  const Outcome ok = run("--width 24 --height 16 --scene " + sh(scene) + " --output " +
                         sh(path("out\t.png")));
  ASSERT_EQ(ok.status, 0) << ok.err;
  EXPECT_NE(ok.out.find("scene " + path("new\\nline.toml") + ":"), std::string::npos) << ok.out;
  EXPECT_NE(ok.out.find("wrote " + path("out\\t.png") + "\n"), std::string::npos) << ok.out;
  EXPECT_EQ(ok.out.find("\nline.toml"), std::string::npos) << ok.out;
  // rt2cpr's own messages about it: escaped.
  const Outcome named = run(std::string(kTiny) + " --scene " + sh(scene) + " --reference " +
                            sh(scene));
  one_line_without_controls(named);
  EXPECT_NE(named.err.find(path("new\\nline.toml")), std::string::npos) << named.err;
  const Outcome esc = run(std::string(kTiny) + " --reference " + sh(path("\x1b[2J\tclear.exr")));
  one_line_without_controls(esc);
  EXPECT_NE(esc.err.find(path("\\x1b[2J\\tclear.exr")), std::string::npos) << esc.err;
  // A warning (an MTL library that is missing) about a name holding ESC.
  write("w.obj", "mtllib gone\x1b[31m.mtl\nv -1 0 0\nv 1 0 0\nv 0 1.5 0\nf 1 2 3\n");
  const Outcome warned = run(std::string(kTiny) + " --scene " + path("w.obj"));
  EXPECT_EQ(warned.status, 0) << warned.err;
  ASSERT_FALSE(warned.err.empty());
  one_line_without_controls(warned);
}

}  // namespace
