// rt2cpr/mpi/render_team.cpp — whole tiles on the rank's threads (see render_team.h).
#include "rt2cpr/mpi/render_team.h"

#include "rt2cpr/clock.h"

namespace rt2cpr::mpi {

std::uint64_t render_whole_tile(const rt2::Renderer& renderer, rt2::Film& film,
                                const rt2::Tile& tile, float* rgb, rt2::RayCounts& rays) {
  for (int p = 0; p < renderer.settings().passes; ++p) renderer.render_tile(tile, p, film, rays);
  const std::uint64_t nonfinite = film.resolve(tile, rgb);
  film.clear(tile);
  return nonfinite;
}

RenderTeam::RenderTeam(const rt2::Renderer& renderer, rt2::Film& film,
                       const rt2::Schedule& schedule)
    : thread_([this, &renderer, &film, schedule] { run_frames(renderer, film, schedule); }) {}

RenderTeam::~RenderTeam() {
  stop();
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    quit_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void RenderTeam::start(Next next, Done done) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    next_ = std::move(next);
    done_ = std::move(done);
    tally_ = {};
    failure_ = nullptr;
    stop_ = failed_ = false;
    rendering_ = 0;
    running_ = true;
  }
  changed_.notify_all();
}

FrameTally RenderTeam::finish() {
  wait_for_end();
  if (failure_) std::rethrow_exception(failure_);
  return tally_;
}

void RenderTeam::stop() {
  stop_ = true;
  wait_for_end();
}

void RenderTeam::wait_for_end() {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [&] { return !running_; });
}

void RenderTeam::run_frames(const rt2::Renderer& renderer, rt2::Film& film,
                            const rt2::Schedule& schedule) {
  const auto work = [&](int) { loop(renderer, film); };
  const int threads = rt2::effective_threads(schedule);
  for (;;) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(lock, [&] { return running_ || quit_; });
      if (quit_) return;
    }
    try {
      rt2::detail::run(schedule.backend, threads, threads, work);  // a loop per thread
    } catch (...) {  // the backend itself (a loop catches its own)
      record_failure();
    }
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      running_ = false;
    }
    changed_.notify_all();
  }
}

void RenderTeam::loop(const rt2::Renderer& renderer, rt2::Film& film) {
  FrameTally mine;
  try {
    while (!stop_ && !failed_) {
      const std::optional<TileOrder> order = next_();
      if (!order) break;
      ++rendering_;
      const auto t0 = Clock::now();
      std::vector<float> rgb(order->tile.pixels() * 3);
      mine.nonfinite_pixels +=
          render_whole_tile(renderer, film, order->tile, rgb.data(), mine.rays);
      mine.busy_ms += ms_since(t0);
      ++mine.tiles;
      done_(*order, std::move(rgb));
      --rendering_;
    }
  } catch (...) {
    record_failure();
  }
  const std::lock_guard<std::mutex> lock(mutex_);
  tally_ += mine;
}

void RenderTeam::record_failure() {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!failure_) failure_ = std::current_exception();
  failed_ = true;
}

}  // namespace rt2cpr::mpi
