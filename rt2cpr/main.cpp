// rt2cpr/main.cpp — the command-line renderer: load a scene, build the BVH, render frames
// with the chosen backend, report timing, write the image and the statistics.
//
// Every failure is one line on stderr ("rt2cpr: ...", failure.h), whatever was thrown and
// wherever, and exit status 1 (2 for a bad command line); output files appear complete or
// not at all (rt2/image/output_file.h).
//
// The same source is rt2cpr_mpi when compiled with RT2CPR_MPI: it then runs in an MPI job
// (rt2cpr/mpi/job.h) whose processes all load the scene and render tiles, while rank 0
// alone prints and writes; otherwise in one process (rt2cpr/local_job.h).
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "rt2/base/error.h"
#include "rt2/image/image_io.h"
#include "rt2/image/output_file.h"
#include "rt2cpr/failure.h"
#include "rt2cpr/frame_files.h"
#include "rt2cpr/options.h"
#include "rt2cpr/report.h"
#include "rt2cpr/scene_setup.h"
#include "rt2cpr/viewer/viewer.h"
#ifdef RT2CPR_MPI
#include "rt2cpr/mpi/job.h"
#else
#include "rt2cpr/local_job.h"
#endif

namespace rt2cpr {

#ifdef RT2CPR_MPI
using Job = mpi::Job;
#else
using Job = LocalJob;
#endif

namespace {

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

// `doing` says what run is doing, for the message of a failure ("out of memory while ...").
int run(const Options& o, Job& job, const char*& doing) {
  if (o.interactive.on) {
    doing = "running the viewer";
    viewer::run_interactive(o);
    return 0;
  }
  // Fail on unwritable outputs, a bad reference and impossible sizes before any work. Only
  // the leader writes files and compares; every process of the job loads the scene.
  rt2::Image reference;
  std::unique_ptr<RenderSetup> setup;
  doing = "loading the scene, building its BVH or allocating the image";
  job.all_or_none([&] {
    if (job.leader() && !o.output.empty()) rt2::check_writable_image(o.output);
    if (job.leader() && !o.stats.empty()) rt2::io::check_output_path(o.stats);
    rt2::check_image_fits(o.render.width, o.render.height);
    if (job.leader()) reference = load_reference(o);
    setup = std::make_unique<RenderSetup>(o);
  });

  Report report(o, setup->scene, setup->compiled, setup->renderer, setup->load_ms,
                setup->build_ms);
  if (job.leader() && !o.quiet) report.print_setup();
  rt2::Image image;
  doing = "rendering";
  // --output with a run of '#': every frame its own file, written as it is done.
  const bool per_frame = !o.output.empty() && names_frames(o.output);
  std::string first_file, last_file;
  job.render_frames(o, *setup, report, image, [&](int f, const rt2::Image& frame) {
    if (!per_frame || !job.leader()) return;
    doing = "writing the image";
    last_file = frame_file(o.output, f + 1);
    rt2::write_image(last_file, frame, o.display);
    if (first_file.empty()) first_file = last_file;
    doing = "rendering";
  });
  if (!job.leader()) return 0;

  // A comparison that fails now still leaves the render written, then reports the failure.
  std::string compare_error;
  if (!o.reference.empty()) {
    doing = "comparing with the reference";
    try {
      report.compare(image, reference);
    } catch (const rt2::Error& e) {
      compare_error = e.what();
    }
  }
  if (!o.quiet) report.print_summary();
  if (per_frame) {
    if (!o.quiet && o.frames == 1) std::printf("wrote %s\n", printable(first_file).c_str());
    if (!o.quiet && o.frames > 1)
      std::printf("wrote %d frames, %s ... %s\n", o.frames, printable(first_file).c_str(),
                  printable(last_file).c_str());
  } else if (!o.output.empty()) {
    doing = "writing the image";
    rt2::write_image(o.output, image, o.display);
    if (!o.quiet) std::printf("wrote %s\n", printable(o.output).c_str());
  }
  if (!o.stats.empty()) {
    doing = "writing the statistics";
    // A path that is not UTF-8 (the scene's, the environment's) is written with U+FFFD in
    // place of its bad bytes: JSON text is UTF-8.
    const std::string json =
        report.json().dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
    rt2::io::write_output_file(o.stats, json);
    if (!o.quiet) std::printf("wrote %s\n", printable(o.stats).c_str());
  }
  if (!compare_error.empty()) throw rt2::Error("comparison with " + o.reference + " failed: " + compare_error);
  return 0;
}

}  // namespace
}  // namespace rt2cpr

namespace {

// The viewer's render threads share the machine with the window's thread and the display
// server, which need a little CPU between two frames. OpenMP's threads spin-wait for the
// next parallel region by default, taking that time away and lowering the frame rate, so
// the viewer runs with OMP_WAIT_POLICY=passive. libgomp reads the policy once, when it is
// loaded, so `--interactive` starts the program again with it set, unless the user chose a
// policy. (Under valgrind /proc/self/exe is valgrind's tool: set OMP_WAIT_POLICY there.)
void exec_with_passive_openmp(int argc, char** argv) {
  bool interactive = false;
  for (int i = 1; i < argc; ++i) interactive |= std::string_view(argv[i]) == "--interactive";
  if (!interactive || std::getenv("OMP_WAIT_POLICY")) return;
  ::setenv("OMP_WAIT_POLICY", "passive", 1);
  ::execv("/proc/self/exe", argv);  // returns only on failure: go on as we are
}

// An exception that escapes where none may (a thread, a destructor, a noexcept function)
// ends the program through std::terminate: it too is one line and status 1, not an abort.
[[noreturn]] void on_terminate() noexcept {
  if (const std::exception_ptr e = std::current_exception()) {
    try {
      std::rethrow_exception(e);
    } catch (...) {
      std::fprintf(stderr, "rt2cpr: %s\n", rt2cpr::failure_message().c_str());
    }
  } else {
    std::fputs("rt2cpr: internal error: terminated without an exception\n", stderr);
  }
  std::_Exit(1);
}

}  // namespace

int main(int argc, char** argv) {
  std::set_terminate(on_terminate);
  exec_with_passive_openmp(argc, argv);
  // Each progress and report line reaches a pipe or a log file as it is printed.
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  std::optional<rt2cpr::Job> job;
  const char* doing = "starting";
  // A failure is printed once, by the leader; the job ends with its status.
  const auto fail = [&](int status) {
    if (!job || job->leader())
      std::fprintf(stderr, "rt2cpr: %s\n", rt2cpr::failure_message(doing).c_str());
    return job ? job->fail(status) : status;
  };
  try {
    job.emplace(argc, argv);
  } catch (...) {
    return fail(1);
  }
  std::optional<rt2cpr::Options> options;
  doing = "reading the command line";
  try {
    job->all_or_none([&] {
      options = rt2cpr::parse_options(argc, argv);
      if (options) job->check(*options);
    });
  } catch (...) {
    return fail(2);
  }
  if (!options) return 0;  // --help, --version
  try {
    return rt2cpr::run(*options, *job, doing);
  } catch (...) {
    return fail(1);
  }
}
