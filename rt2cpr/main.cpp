// rt2cpr/main.cpp — the command-line renderer: load a scene, build the BVH, render frames
// with the chosen backend, report timing, write the image and the statistics.
//
// Every failure is one line on stderr ("rt2cpr: ...") and exit status 1 (2 for a bad
// command line); output files appear complete or not at all (rt2/io/output_file.h).
#include <algorithm>
#include <cstdio>
#include <new>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <unistd.h>
#include <cstdlib>
#include <vector>

#include "rt2/compiled_scene.h"
#include "rt2/error.h"
#include "rt2/image_io.h"
#include "rt2/io/output_file.h"
#include "rt2cpr/options.h"
#include "rt2cpr/progress.h"
#include "rt2cpr/report.h"
#include "rt2cpr/scene_setup.h"
#include "rt2cpr/viewer/viewer.h"

namespace rt2cpr {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// The reference image, read and checked before the first frame so that a typo, a file
// that is not an image or a size mismatch does not throw a long render away.
rt2::Image load_reference(const Options& o) {
  if (o.reference.empty()) return {};
  rt2::Image ref = rt2::read_image(o.reference);
  if (ref.width != o.render.width || ref.height != o.render.height)
    throw rt2::Error(o.reference + ": reference image is " + std::to_string(ref.width) + "x" +
                     std::to_string(ref.height) + ", the render is " +
                     std::to_string(o.render.width) + "x" + std::to_string(o.render.height));
  return ref;
}

int run(const Options& o) {
  if (o.interactive.on) {
    viewer::run_interactive(o);
    return 0;
  }
  // Fail on unwritable outputs, a bad reference and impossible sizes before any work.
  if (!o.output.empty()) rt2::check_writable_image(o.output);
  if (!o.stats.empty()) rt2::io::check_output_path(o.stats);
  rt2::check_image_fits(o.render.width, o.render.height);
  const rt2::Image reference = load_reference(o);

  auto t0 = Clock::now();
  rt2::Scene scene = load_scene(o);
  set_lights(scene, o.lights, o.light_range);
  const double load_ms = ms_since(t0);

  t0 = Clock::now();
  rt2::CompiledScene compiled = compile_at_camera(scene, o);
  const double build_ms = ms_since(t0);
  const rt2::Renderer renderer(compiled, rt2::View{scene.camera, o.render});

  Report report(o, scene, compiled, renderer, load_ms, build_ms);
  if (!o.quiet) report.print_setup();

  rt2::Image image;
  rt2::Film film(o.render.width, o.render.height);
  ProgressBar bar(!o.quiet);
  const int passes = o.render.passes;
  for (int f = 0; f < o.frames; ++f) {
    bar.start_frame(f, o.frames);
    if (f > 0) film.clear();
    rt2::FrameResult frame;
    const auto start = Clock::now();
    // The frame's lights: moved and their tree rebuilt, inside the frame's time.
    if (o.animate_lights)
      report.add_light_update(compiled.move_lights(f / 30.0, rt2::effective_threads(o.schedule)));
    int done = 0;
    double last_pass_ms = 0.0;
    for (int p = 0; p < passes; ++p) {
      // --time-budget: the next pass only if it fits, guessing it takes as long as the last.
      if (p > 0 && o.time_budget > 0.0 && ms_since(start) + last_pass_ms > o.time_budget * 1e3)
        break;
      const rt2::FrameResult r = rt2::render_pass(renderer, o.schedule, film, p, [&](int d, int n) {
        bar.update(p * n + d, passes * n);
      });
      frame.rays += r.rays;
      frame.portions = r.portions;
      last_pass_ms = r.ms;
      ++done;
      if (!o.quiet && passes > 1 && o.frames == 1)
        std::printf("pass %d of %d: %.2f ms\n", p + 1, passes, r.ms);
    }
    frame.ms = ms_since(start);
    frame.nonfinite_pixels = film.resolve(image);
    bar.end_frame();
    report.add_frame(frame, done);
    if (!o.quiet && o.frames > 1) std::printf("frame %d: %.2f ms\n", f + 1, frame.ms);
  }
  // A comparison that fails now still leaves the render written, then reports the failure.
  std::string compare_error;
  if (!o.reference.empty()) {
    try {
      report.compare(image, reference);
    } catch (const rt2::Error& e) {
      compare_error = e.what();
    }
  }
  if (!o.quiet) report.print_summary();
  if (!o.output.empty()) {
    rt2::write_image(o.output, image, o.display);
    if (!o.quiet) std::printf("wrote %s\n", o.output.c_str());
  }
  if (!o.stats.empty()) {
    rt2::io::write_output_file(o.stats, report.json().dump(2) + "\n");
    if (!o.quiet) std::printf("wrote %s\n", o.stats.c_str());
  }
  if (!compare_error.empty()) throw rt2::Error("comparison with " + o.reference + " failed: " + compare_error);
  return 0;
}

}  // namespace
}  // namespace rt2cpr

// The viewer's render threads share the machine with the window's thread and the display
// server, which need a little CPU between two frames. OpenMP's threads spin-wait for the
// next parallel region by default, taking that time away: on 2 cores the viewer showed 25
// frames/s with OMP_WAIT_POLICY=active and 39 with passive (scripts/bench-viewer). libgomp
// reads the policy once, when it is loaded, so `--interactive` starts the program again with
// it set, unless the user chose a policy.
void exec_with_passive_openmp(int argc, char** argv) {
  bool interactive = false;
  for (int i = 1; i < argc; ++i) interactive |= std::string_view(argv[i]) == "--interactive";
  if (!interactive || std::getenv("OMP_WAIT_POLICY")) return;
  ::setenv("OMP_WAIT_POLICY", "passive", 1);
  ::execv("/proc/self/exe", argv);  // returns only on failure: go on as we are
}

int main(int argc, char** argv) {
  exec_with_passive_openmp(argc, argv);
  // Each progress and report line reaches a pipe or a log file as it is printed.
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  std::optional<rt2cpr::Options> options;
  try {
    options = rt2cpr::parse_options(argc, argv);
  } catch (const rt2::Error& e) {
    std::fprintf(stderr, "rt2cpr: %s\n", e.what());
    return 2;
  }
  if (!options) return 0;  // --help, --version
  try {
    return rt2cpr::run(*options);
  } catch (const rt2::Error& e) {
    std::fprintf(stderr, "rt2cpr: %s\n", e.what());
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "rt2cpr: out of memory\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rt2cpr: internal error: %s\n", e.what());
  }
  return 1;
}
