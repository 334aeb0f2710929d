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
#include <vector>

#include "rt2/builtin_scene.h"
#include "rt2/error.h"
#include "rt2/image_io.h"
#include "rt2/io/output_file.h"
#include "rt2/scene_io.h"
#include "rt2cpr/options.h"
#include "rt2cpr/progress.h"
#include "rt2cpr/report.h"

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
  // Fail on unwritable outputs, a bad reference and impossible sizes before any work.
  if (!o.output.empty()) rt2::check_writable_image(o.output);
  if (!o.stats.empty()) rt2::io::check_output_path(o.stats);
  rt2::check_image_fits(o.render.width, o.render.height);
  const rt2::Image reference = load_reference(o);

  auto t0 = Clock::now();
  rt2::Scene scene = o.scene.empty() ? rt2::make_default_scene() : rt2::load_scene(o.scene);
  if (o.lights >= 0) rt2::set_light_count(scene, static_cast<std::size_t>(o.lights));
  scene.validate();
  rt2::recenter_on_camera(scene);  // full float precision where the pixels come from
  const double load_ms = ms_since(t0);

  t0 = Clock::now();
  const rt2::Accel accel = rt2::Accel::build(scene, o.bvh, o.isa);
  const double build_ms = ms_since(t0);
  const rt2::Renderer renderer(scene, accel, o.render);

  Report report(o, scene, accel, renderer, load_ms, build_ms);
  if (!o.quiet) report.print_setup();

  rt2::Image image;
  ProgressBar bar(!o.quiet);
  for (int f = 0; f < o.frames; ++f) {
    bar.start_frame(f, o.frames);
    const rt2::FrameResult r = rt2::render_frame(
        renderer, o.schedule, image, [&](int done, int total) { bar.update(done, total); });
    bar.end_frame();
    report.add_frame(r);
    if (!o.quiet && o.frames > 1) std::printf("frame %d: %.2f ms\n", f + 1, r.ms);
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
    rt2::write_image(o.output, image);
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

int main(int argc, char** argv) {
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
