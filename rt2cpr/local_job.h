// rt2cpr/local_job.h — the processes rt2cpr runs in: one, which prints, writes the files
// and renders every tile with its own threads.
//
// main.cpp is written against a job: `leader()` (the process that prints and writes),
// `all_or_none(step)` (a step every process takes, failing everywhere when it fails
// anywhere), `check(options)`, `render_frames` and `fail(status)` (the end of a job whose
// failure the leader has printed). rt2cpr_mpi compiles the same main with an MPI job
// instead (rt2cpr/mpi/job.h).
#pragma once

#include "rt2/image/image.h"
#include "rt2cpr/frame_files.h"
#include "rt2cpr/options.h"
#include "rt2cpr/report.h"
#include "rt2cpr/scene_setup.h"

namespace rt2cpr {

class LocalJob {
 public:
  LocalJob(int& /*argc*/, char**& /*argv*/) {}

  static constexpr bool leader() { return true; }
  // Runs `step`: with no other process to agree with, its exception is the job's.
  template <class Step>
  void all_or_none(Step&& step) { step(); }
  // Throws rt2::Error for an option of rt2cpr_mpi's (--rank0 serve: no one would render).
  void check(const Options& o) const;

  // Renders the frames of `o` in passes (--passes, --time-budget), an animated scene posed
  // and the lights moved (--animate-lights) before each, adding each frame to `report`;
  // each frame's mean into `image`, then given to `each` with its index.
  void render_frames(const Options& o, RenderSetup& setup, Report& report, rt2::Image& image,
                     const FrameSink& each);

  // The process exits with `status`.
  static int fail(int status) { return status; }
};

}  // namespace rt2cpr
