// rt2cpr/mpi/job.cpp — an MPI job's frames (see job.h).
#include "rt2cpr/mpi/job.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <optional>
#include <thread>

#include "rt2/base/error.h"
#include "rt2/render/schedule.h"
#include "rt2cpr/clock.h"
#include "rt2cpr/mpi/calls.h"
#include "rt2cpr/mpi/protocol.h"
#include "rt2cpr/mpi/render_team.h"
#include "rt2cpr/mpi/root_frame.h"
#include "rt2cpr/mpi/worker_frame.h"
#include "rt2cpr/progress.h"

namespace rt2cpr::mpi {
namespace {

// What every rank tells the others before the first frame.
struct Peer {
  std::int32_t threads = 0;
  char host[60] = {};
};

// The tiles of a frame: --tile N squares, as in one process; by default (--tile 0) bands of
// rows, threads x grain of them over all the ranks' threads (at most one per row).
std::vector<rt2::Tile> job_tiles(const Options& o, int all_threads) {
  if (o.schedule.tile == 0)
    return rt2::make_bands(o.render.width, o.render.height,
                           static_cast<long long>(all_threads) * o.schedule.grain);
  return rt2::make_tiles(o.schedule, o.render.width, o.render.height);
}

// Rank 0, while it waits: a worker's failure ends the wait (and the job).
void watch_for_errors() {
  int found = 0;
  MPI_Status st;
  check(MPI_Iprobe(MPI_ANY_SOURCE, kError, MPI_COMM_WORLD, &found, &st), "MPI_Iprobe");
  if (found) throw rt2::Error(text_of(receive(st)));
}

}  // namespace

Job::Job(int& argc, char**& argv) : session_(argc, argv), notice_(session_.root()) {}

void Job::check(const Options& o) const {
  if (!o.rank0_renders && session_.size() < 2)
    throw rt2::Error("--rank0 serve: rank 0 renders nothing, so the job needs 2 processes or more");
  if (o.interactive.on)
    throw rt2::Error("--interactive: rt2cpr_mpi renders files; the window is rt2cpr's");
  if (o.time_budget > 0.0)
    throw rt2::Error("--time-budget: rt2cpr_mpi renders every pass of a tile at once, so it "
                     "cannot stop between passes; rt2cpr can");
}

void Job::render_frames(const Options& o, RenderSetup& setup, Report& report, rt2::Image& image,
                        const FrameSink& each) {
  all_or_none([&] {
    if (leader()) image = rt2::Image(o.render.width, o.render.height);
  });
  try {
    frames(o, setup, report, image, each);
  } catch (...) {
    stop(failure_message());
  }
  notice_.release();
}

int Job::fail(int status) const {
  if (session_.root()) session_.abort(status);
  return status;
}

void Job::stop(const std::string& failure) const {
  if (!session_.root()) {
    // Rank 0 prints it and ends the job; this rank waits for that.
    try {
      send_text(0, kError, session_.name() + ": " + failure);
      for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
    } catch (...) {
      // Rank 0 cannot be told: say it here.
    }
  }
  const std::string who = session_.root() ? "" : session_.name() + ": ";
  std::fprintf(stderr, "rt2cpr: %s%s\n", who.c_str(), failure.c_str());
  session_.abort(1);
}

void Job::frames(const Options& o, RenderSetup& setup, Report& report, rt2::Image& image,
                 const FrameSink& each) {
  const Between watch = leader() ? Between(watch_for_errors) : Between();
  const int threads = rt2::effective_threads(o.schedule);
  Peer me;
  me.threads = leader() && !o.rank0_renders ? 0 : threads;
  std::strncpy(me.host, session_.host().c_str(), sizeof me.host - 1);
  const std::vector<Peer> peers = allgather(me, watch);

  std::vector<RankStats> ranks(peers.size());
  int all_threads = 0;
  for (std::size_t r = 0; r < peers.size(); ++r) {
    ranks[r] = {.rank = int(r), .host = peers[r].host, .threads = peers[r].threads};
    all_threads += peers[r].threads;
  }
  // Every rank knows the tiles (their count sets the workers' credits); rank 0 hands them out.
  const std::vector<rt2::Tile> tiles = job_tiles(o, all_threads);
  const auto credits_of = [&](std::size_t r) {
    return credits(peers[r].threads, tiles.size(), all_threads);
  };
  int chains = 0;
  for (std::size_t r = 1; r < peers.size(); ++r) chains += credits_of(r);
  if (leader() && !o.quiet)
    std::printf("MPI: %d processes, %d render threads in all%s; %zu tiles a frame, handed out as "
                "they are asked for\n", session_.size(), all_threads,
                o.rank0_renders ? "" : " (rank 0 serves only)", tiles.size());

  std::optional<RenderTeam> team;
  if (!leader() || o.rank0_renders) team.emplace(setup.renderer, setup.film, o.schedule);
  ProgressBar bar(leader() && !o.quiet);
  for (int f = 0; f < o.frames; ++f) {
    bar.start_frame(f, o.frames);
    const auto start = Clock::now();
    // The frame's pose of an animated scene, by every rank alike, inside the frame's time.
    std::optional<RenderSetup::PoseTimes> posed;
    if (f > 0) all_or_none([&] { posed = setup.pose(o, f); });
    if (posed && leader()) report.add_pose(posed->load_ms, posed->place_ms, posed->placed);
    // The frame's lights, moved by every rank alike, inside the frame's time.
    if (o.animate_lights) {
      const rt2::LightBvh::BuildTimes t = setup.compiled.move_lights(frame_seconds(o, f), threads);
      if (leader()) report.add_light_update(t);
    }
    const auto progress = [&](int in, int n) { bar.update(in, n); };
    const FrameTally mine =
        leader() ? render_root_frame({team ? &*team : nullptr, tiles, chains, image, progress})
                 : render_worker_frame(*team, credits_of(std::size_t(session_.rank())));
    rt2::FrameResult frame;
    frame.ms = ms_since(start);
    const std::vector<FrameTally> all = allgather(mine, watch);
    if (!leader()) continue;
    frame.portions = static_cast<int>(tiles.size());
    for (std::size_t r = 0; r < all.size(); ++r) {
      frame.rays += all[r].rays;
      frame.nonfinite_pixels += all[r].nonfinite_pixels;
      ranks[r].tiles += all[r].tiles;
      ranks[r].bytes_sent += all[r].bytes_sent;
      ranks[r].busy_ms += all[r].busy_ms;
      ranks[r].serve_ms += all[r].serve_ms;
    }
    bar.end_frame();
    report.add_frame(frame, o.render.passes);
    if (!o.quiet && o.frames > 1) std::printf("frame %d: %.2f ms\n", f + 1, frame.ms);
    each(f, image);
  }
  report.set_ranks(std::move(ranks));
}

}  // namespace rt2cpr::mpi
