// `rt2cpr --interactive` in a real window: an X server of its own (Xvfb, through Debian's
// xvfb-run) per test, the input played by --script through SDL's event queue as a user's
// would be. The oracle is the file render: the converged still equals `rt2cpr --camera
// <the printed camera> --output` bit for bit, and the window shows that image.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <regex>
#include <string>

#include "rt2/image/image_io.h"
#include "rt2/image/srgb.h"
#include "tests/rt2cpr/cli_fixture.h"

namespace {

using rt2::test::Outcome;
namespace fs = std::filesystem;

class Interactive : public rt2::test::Cli {
 protected:
  void SetUp() override {
    if (!RT2_HAVE_VIEWER) FAIL() << "rt2cpr was built without the viewer (libsdl2-dev, libimgui-dev)";
    ASSERT_EQ(std::system("command -v xvfb-run >/dev/null"), 0) << "xvfb-run is missing (Debian's xvfb)";
  }
  // rt2cpr in a window of an X server of its own, from the test's folder. Its exit status
  // is read from a file a shell inside xvfb-run writes: xvfb-run's own status can replace
  // the program's (5 when it could not clean up its temporary folder, seen under load).
  Outcome run_window(const std::string& args) const {
    std::filesystem::remove(path("status"));
    Outcome o = run_in("cd " + dir_.root().string() + " && " + std::string(rt2::test::kChildEnv) +
                       "xvfb-run -a -s '-screen 0 1024x768x24' sh -c '" + RT2CPR_BIN +
                       " --interactive " + args + "; echo $? >" + path("status") + "'");
    const std::string status = slurp(path("status"));
    if (!status.empty()) o.status = std::stoi(status);  // else xvfb-run's (it did not start)
    return o;
  }
  Outcome run_in(const std::string& cmd) const {
    const int raw = std::system((cmd + " >" + path("stdout") + " 2>" + path("stderr")).c_str());
    return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(path("stdout")), slurp(path("stderr"))};
  }
  // The last [camera] table the viewer printed (its C key), written to `name`.
  std::string printed_camera(const std::string& out, const std::string& name) const {
    const std::size_t at = out.rfind("[camera]");
    EXPECT_NE(at, std::string::npos) << out;
    std::string table;
    std::size_t end = at;
    for (int lines = 0; lines < 5 && end != std::string::npos; ++lines) end = out.find('\n', end + 1);
    table = out.substr(at, end == std::string::npos ? std::string::npos : end - at + 1);
    write(name, table);
    return path(name);
  }
};

double mean(const rt2::Image& img) {
  double s = 0.0;
  for (float v : img.rgb) s += v;
  return s / double(img.rgb.size());
}

double stddev(const rt2::Image& img) {
  const double m = mean(img);
  double s = 0.0;
  for (float v : img.rgb) s += (v - m) * (v - m);
  return std::sqrt(s / double(img.rgb.size()));
}

const char* kSize = "--width 96 --height 72 --depth 4 --subpixels 4 --threads 2";

// The scripted flight: the window shows the scene, the moved camera changes the
// image, and the converged still is the file render of the camera the viewer printed.
TEST_F(Interactive, AScriptedFlightShowsTheSceneMovesItAndConvergesToTheFileRender) {
  write("flight.txt",
        "wait-still\n"
        "screenshot first.exr\n"
        "window-shot window.png\n"
        "key W 0.3\n"
        "mouse 60 -15\n"
        "key D 0.2\n"
        "wait-still\n"
        "key C\n"
        "screenshot still.exr\n"
        "quit\n");
  const Outcome r = run_window(std::string(kSize) + " --script flight.txt");
  ASSERT_EQ(r.status, 0) << r.err;
  const rt2::Image first = rt2::read_image(path("first.exr"));
  const rt2::Image window = rt2::read_image(path("window.png"));
  const rt2::Image still = rt2::read_image(path("still.exr"));
  // Not black: lit, with structure (a flat colour would have no spread).
  EXPECT_GT(mean(first), 0.05);
  EXPECT_GT(stddev(first), 0.05);
  EXPECT_GT(mean(window), 0.05);
  EXPECT_GT(stddev(window), 0.05);
  // The camera moved: the image changed.
  ASSERT_EQ(still.width, first.width);
  std::size_t changed = 0;
  for (std::size_t i = 0; i < still.rgb.size(); ++i) changed += still.rgb[i] != first.rgb[i];
  EXPECT_GT(changed, still.rgb.size() / 4);
  // The converged still is the file render from the printed camera, bit for bit; and the
  // first still, before any move, the file render of the scene's own camera.
  const std::string cam = printed_camera(r.out, "cam.toml");
  ASSERT_EQ(run(std::string(kSize) + " --quiet --camera " + cam + " --output " + path("ref.exr")).status, 0);
  EXPECT_EQ(still.rgb, rt2::read_image(path("ref.exr")).rgb);
  ASSERT_EQ(run(std::string(kSize) + " --quiet --output " + path("ref0.exr")).status, 0);
  EXPECT_EQ(first.rgb, rt2::read_image(path("ref0.exr")).rgb);
}

// With the panel off and the window the render's size, what the window shows is the image:
// each pixel within one 8-bit step of the file's (the screen's sRGB table,
// rt2/image/display_pixels.h).
TEST_F(Interactive, TheWindowShowsTheImage) {
  write("s.txt", "set overlay off\nwait-still\nscreenshot img.png\nwindow-shot win.png\nquit\n");
  const Outcome r = run_window(std::string(kSize) + " --script s.txt");
  ASSERT_EQ(r.status, 0) << r.err;
  const rt2::Image img = rt2::read_image(path("img.png")), win = rt2::read_image(path("win.png"));
  ASSERT_EQ(win.width, img.width);
  ASSERT_EQ(win.height, img.height);
  double worst = 0.0;
  for (std::size_t i = 0; i < img.rgb.size(); ++i)
    worst = std::max(worst, std::fabs(double(rt2::srgb_encode(img.rgb[i])) - rt2::srgb_encode(win.rgb[i])));
  EXPECT_LE(worst, 1.5 / 255.0);
}

// Every setting changed mid-render, the window resized twice, the backend and threads
// swapped: the still converges to the file render with those settings.
TEST_F(Interactive, SettingsChangedMidFrameConvergeToTheirFileRender) {
  write("s.txt",
        "set subpixels 9\n"
        "wait 0.05\n"
        "set depth 8\n"
        "resize 300 200\n"
        "set backend tbb\n"
        "set threads 1\n"
        "set lights 3\n"
        "resize 120 400\n"
        "set pattern circle\n"
        "set triangle-test watertight\n"
        "set min-weight 0.05\n"
        "set subpixels 2\n"
        "wait-still\n"
        "key C\n"
        "screenshot s.exr\n"
        "quit\n");
  const Outcome r = run_window(std::string(kSize) + " --script s.txt");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string cam = printed_camera(r.out, "cam.toml");
  ASSERT_EQ(run("--width 96 --height 72 --quiet --depth 8 --subpixels 2 --pattern circle --lights 3 "
                "--triangle-test watertight --min-weight 0.05 --camera " + cam + " --output " + path("ref.exr"))
                .status, 0);
  EXPECT_EQ(rt2::read_image(path("s.exr")).rgb, rt2::read_image(path("ref.exr")).rgb);
}

// The screenshot key (--screenshot-key; F12 by default) writes through --output's writer,
// or to rt2cpr-N.png in the current folder without --output.
TEST_F(Interactive, TheScreenshotKeyWritesTheImage) {
  write("s.txt", "wait-still\nkey P\nwait 0.05\nquit\n");
  Outcome r = run_window(std::string(kSize) + " --script s.txt --screenshot-key P --output shot.png");
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_EQ(run(std::string(kSize) + " --quiet --output " + path("ref.png")).status, 0);
  EXPECT_EQ(rt2::read_image(path("shot.png")).rgb, rt2::read_image(path("ref.png")).rgb);
  write("t.txt", "wait-still\nkey F12\nkey F12\nwait 0.05\nquit\n");
  r = run_window(std::string(kSize) + " --script t.txt");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(rt2::read_image(path("rt2cpr-1.png")).rgb, rt2::read_image(path("ref.png")).rgb);
  EXPECT_TRUE(fs::exists(path("rt2cpr-2.png")));
}

// Closed while a long still renders: the window goes at once, exit 0; the frame log says
// what was shown.
TEST_F(Interactive, QuittingMidRenderEndsCleanlyAndWritesTheFrameLog) {
  write("s.txt", "wait 1\nkey W 0.2\nwait 0.3\nquit\n");
  const Outcome r = run_window("--width 200 --height 150 --subpixels 4096 --script s.txt --frame-log log.csv");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string log = slurp(path("log.csv"));
  EXPECT_EQ(log.rfind("time_s,kind,pass,passes,width,height,render_ms,rays\n", 0), 0u);
  EXPECT_NE(log.find(",moving,"), std::string::npos) << log;
  EXPECT_NE(log.find(",still,"), std::string::npos) << log;
  EXPECT_NE(r.out.find("moving: "), std::string::npos) << r.out;
}

TEST_F(Interactive, NoDisplayIsOneLineAndExitOne) {
  const Outcome r = run_in(std::string(rt2::test::kChildEnv) + "env -u DISPLAY -u WAYLAND_DISPLAY " +
                           RT2CPR_BIN + " --interactive");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
  EXPECT_NE(r.err.find("needs a display"), std::string::npos) << r.err;
}

// A display that is named but cannot be opened: SDL's reason, in one line.
TEST_F(Interactive, ADisplayThatCannotBeOpenedIsOneLineAndExitOne) {
  const Outcome r = run_in(std::string(rt2::test::kChildEnv) + "env -u WAYLAND_DISPLAY DISPLAY=:31999 " +
                           RT2CPR_BIN + " --interactive");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
  EXPECT_NE(r.err.find("no display could be opened"), std::string::npos) << r.err;
}

// A bad script is found before any window opens: one line naming the file and line.
TEST_F(Interactive, ABadScriptIsOneLineWithItsFileAndLine) {
  write("bad.txt", "wait 0.1\njump 3\n");
  expect_clean_failure(run("--interactive --script " + path("bad.txt")), "bad.txt:2: unknown command 'jump'");
  write("key.txt", "key Hyperdrive\n");
  expect_clean_failure(run("--interactive --script " + path("key.txt")), "key.txt:1: unknown key 'Hyperdrive'");
  expect_clean_failure(run("--interactive --screenshot-key Hyperdrive"), "unknown key 'Hyperdrive'");
  write("set.txt", "wait 1\nset detph 8\n");
  expect_clean_failure(run("--interactive --script " + path("set.txt")), "set.txt:2: unknown setting 'detph'");
  write("value.txt", "set depth -3\n");
  expect_clean_failure(run("--interactive --script " + path("value.txt")), "value.txt:1: depth must be");
}

// R takes the camera back to the scene's: the still is the file render of the scene.
TEST_F(Interactive, ResetReturnsToTheScenesCamera) {
  write("s.txt", "key W 0.3\nmouse 40 20\nscroll 3\nkey A 0.2\nkey R\nwait-still\nscreenshot r.exr\nquit\n");
  const Outcome r = run_window(std::string(kSize) + " --script s.txt");
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_EQ(run(std::string(kSize) + " --quiet --output " + path("ref.exr")).status, 0);
  EXPECT_EQ(rt2::read_image(path("r.exr")).rgb, rt2::read_image(path("ref.exr")).rgb);
}

// Frames slower than --target-fps lower the resolution: with a target no frame can meet,
// the moving frames shrink (the frame log says so) and the still is full size again.
TEST_F(Interactive, MovingFramesUnderTheTargetRateLowerTheResolution) {
  write("s.txt", "key W 1.5\nwait-still\nquit\n");
  const Outcome r = run_window("--width 160 --height 120 --target-fps 1000 --script s.txt --frame-log log.csv");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string log = slurp(path("log.csv"));
  EXPECT_NE(log.find(",moving,0,1,80,60,"), std::string::npos) << log;  // 1/2
  EXPECT_NE(log.find(",still,1,1,160,120,"), std::string::npos) << log;
}

// A setting the scene cannot take fails every request: wait-still says why at once, and
// the run fails naming the script's line.
TEST_F(Interactive, WaitStillFailsAtOnceWhenTheViewCannotBeRendered) {
  write("s.txt", "set lights 1\nwait-still\nquit\n");  // --light-range then applies to no light
  const Outcome r = run_window(std::string(kSize) + " --lights 3 --light-range 2 --script s.txt");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("s.txt:2: the image cannot converge: --light-range applies"), std::string::npos)
      << r.err;
}

// A still that cannot converge in the time the script allows fails the run, naming the line.
TEST_F(Interactive, AStillThatDoesNotConvergeInTimeFailsTheScript) {
  write("s.txt", "wait 0.1\nwait-still 0\nquit\n");
  const Outcome r = run_window("--width 320 --height 240 --subpixels 65536 --script s.txt");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("s.txt:2: the image did not converge within 0 s"), std::string::npos) << r.err;
}

}  // namespace
