// rt2cpr/mpi/job.h — the processes rt2cpr_mpi runs in: an MPI job. Every rank loads and
// compiles the scene (replicated data, as OSPRay's replicated mode) and renders tiles with
// its own threads; rank 0 hands the tiles out as they are asked for and renders too,
// assembles the image, prints, and writes the output and the statistics once. The
// interface is LocalJob's (rt2cpr/local_job.h), for rt2cpr/main.cpp.
#pragma once

#include <optional>
#include <string>

#include "rt2/image/image.h"
#include "rt2cpr/failure.h"
#include "rt2cpr/frame_files.h"
#include "rt2cpr/mpi/agreement.h"
#include "rt2cpr/mpi/session.h"
#include "rt2cpr/mpi/stop_notice.h"
#include "rt2cpr/options.h"
#include "rt2cpr/report.h"
#include "rt2cpr/scene_setup.h"

namespace rt2cpr::mpi {

// How each kind of failure ends the job (no output is written in any of these cases):
// - a step every rank takes (the options, the scene, the film) and that fails on any rank:
//   every rank stops after it (agreement.h), and rank 0 prints the first failure's line and
//   ends the job with status 1 (2 for the options) by MPI_Abort, at once: mpirun lets a
//   second or two pass before it reports a process that exits with a non-zero status;
// - a failure while frames render: a worker sends its line to rank 0, which prints it and
//   aborts the job (MPI_Abort, status 1); rank 0's own is printed the same way;
// - a process that dies: mpirun ends the job, and rank 0 says so (stop_notice.h).
class Job {
 public:
  Job(int& argc, char**& argv);

  bool leader() const { return session_.root(); }
  // Runs `step` on this rank, then agrees with every other rank (agreement.h): throws on
  // every rank when it failed on any.
  template <class Step>
  void all_or_none(Step&& step) {
    std::optional<std::string> failure;
    try {
      step();
    } catch (...) {
      failure = failure_message();
    }
    agree(session_, failure);
  }
  // Throws rt2::Error for what an MPI job does not do: --interactive, --time-budget, and
  // --rank0 serve with one process.
  void check(const Options& o) const;

  // Renders the frames of `o` with every rank, each frame's tiles handed out by rank 0
  // (root_frame.h, worker_frame.h), adding each frame to `report` and, at the end, each
  // rank's figures; an animated scene posed by every rank before each frame; on rank 0,
  // each frame into `image`, then given to `each`. A failure ends the job here.
  void render_frames(const Options& o, RenderSetup& setup, Report& report, rt2::Image& image,
                     const FrameSink& each);

  // Rank 0 ends the job with `status` (MPI_Abort); another rank returns it, and then waits
  // at MPI_Finalize to be ended.
  int fail(int status) const;

 private:
  void frames(const Options& o, RenderSetup& setup, Report& report, rt2::Image& image,
              const FrameSink& each);
  [[noreturn]] void stop(const std::string& failure) const;

  Session session_;
  StopNotice notice_;
};

}  // namespace rt2cpr::mpi
