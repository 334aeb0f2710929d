// rt2cpr/mpi/render_team.h — one rank's render threads, rendering whole tiles.
//
// The unit of work of an MPI job is a whole tile: every pass of it rendered into the rank's
// film, in pass order, then its pixels' means taken out (Film::resolve of the tile) and
// its part of the film emptied for the next frame. Each pixel's samples are thus added in
// the order one process adds them, pass after pass, and its mean is the same bits; only
// the means travel (12 bytes a pixel, whatever the samples).
#pragma once

#include <atomic>
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "rt2/image/film.h"
#include "rt2/render/renderer.h"
#include "rt2/render/schedule.h"
#include "rt2cpr/mpi/frame_tally.h"
#include "rt2cpr/mpi/protocol.h"

namespace rt2cpr::mpi {

// Renders every pass of `tile` into `film` and takes its means out into `rgb`
// (tile.pixels() x 3 floats, row by row), leaving the tile's pixels of the film empty.
// Returns the means that were NaN or infinite (written as black: Film::resolve).
std::uint64_t render_whole_tile(const rt2::Renderer& renderer, rt2::Film& film,
                                const rt2::Tile& tile, float* rgb, rt2::RayCounts& rays);

// One rank's render threads, started once for the job (as one process keeps its OpenMP or
// oneTBB threads from frame to frame, with their scratch memory warm). Each frame runs as
// many loops as the schedule has threads, by its backend (OpenMP, oneTBB, or one loop for
// serial), on a thread of their own, so that the thread that made the team stays free for
// MPI. Each loop takes a tile from `next` until it gives none, renders it whole and hands
// its means to `done`; both are called from the render threads, concurrently.
class RenderTeam {
 public:
  using Next = std::function<std::optional<TileOrder>()>;
  using Done = std::function<void(const TileOrder&, std::vector<float>&& rgb)>;

  RenderTeam(const rt2::Renderer& renderer, rt2::Film& film, const rt2::Schedule& schedule);
  // stop(), then ends the thread.
  ~RenderTeam();
  RenderTeam(const RenderTeam&) = delete;
  RenderTeam& operator=(const RenderTeam&) = delete;

  // Starts a frame's loops (the last frame's must have ended: finish or stop).
  void start(Next next, Done done);
  // True once a loop has failed (it and the others then take no more tiles).
  bool failed() const { return failed_; }
  // True while a loop renders a tile (false while they all wait in `next` or have ended).
  bool rendering() const { return rendering_ > 0; }
  // Waits for the frame's loops to end (when `next` gives nothing); rethrows the first
  // failure. The frame's rays, tiles, busy time and non-finite pixels (the bytes and
  // serving time are the caller's).
  FrameTally finish();
  // Lets each loop finish its tile, takes no more, and waits for them (a loop waiting in
  // `next` must be released by its owner first: a closed Channel). Never throws.
  void stop();

 private:
  void run_frames(const rt2::Renderer& renderer, rt2::Film& film,
                  const rt2::Schedule& schedule);
  void loop(const rt2::Renderer& renderer, rt2::Film& film);
  void record_failure();  // inside a catch block: the first failure is kept
  void wait_for_end();

  Next next_;
  Done done_;
  std::atomic<bool> stop_ = false, failed_ = false;
  std::atomic<int> rendering_ = 0;
  std::mutex mutex_;  // guards what follows
  std::condition_variable changed_;
  bool running_ = false, quit_ = false;  // a frame's loops run; the thread is to end
  FrameTally tally_;
  std::exception_ptr failure_;
  std::thread thread_;  // last: starts once the members above exist
};

}  // namespace rt2cpr::mpi
