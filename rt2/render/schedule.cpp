// rt2/render/schedule.cpp — frame splitting, the serial and OpenMP backends.
#include "rt2/render/schedule.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>

#include "rt2/base/error.h"

namespace rt2 {

const char* backend_name(Backend b) {
  switch (b) {
    case Backend::serial: return "serial";
    case Backend::omp: return "omp";
    case Backend::tbb: return "tbb";
  }
  return "?";
}

Backend parse_backend(const std::string& name) {
  if (name == "serial") return Backend::serial;
  if (name == "omp") return Backend::omp;
  if (name == "tbb") return Backend::tbb;
  throw Error("unknown backend '" + name + "' (expected serial, omp or tbb)");
}

int effective_threads(const Schedule& s) {
  if (s.backend == Backend::serial) return 1;
  if (s.threads > 0) return s.threads;
  return std::max(1u, std::thread::hardware_concurrency());
}

namespace detail {

void run_serial(int portions, const std::function<void(int)>& work) {
  for (int i = 0; i < portions; ++i) work(i);
}

void run_omp(int threads, int portions, const std::function<void(int)>& work) {
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
  for (int i = 0; i < portions; ++i) work(i);
}

void run(Backend backend, int threads, int portions, const std::function<void(int)>& work) {
  switch (backend) {
    case Backend::serial: run_serial(portions, work); break;
    case Backend::omp: run_omp(threads, portions, work); break;
    case Backend::tbb: run_tbb(threads, portions, work); break;
  }
}

}  // namespace detail

std::vector<Tile> make_tiles(const Schedule& schedule, int width, int height) {
  if (schedule.threads < 0 || schedule.threads > 1024)
    throw Error("threads must be in [1, 1024] (0 = all hardware threads), got " +
                std::to_string(schedule.threads));
  if (schedule.grain < 1 || schedule.grain > 1'000'000)
    throw Error("grain must be in [1, 1000000], got " + std::to_string(schedule.grain));
  if (schedule.tile < 0 || schedule.tile > 65535)
    throw Error("tile must be in [1, 65535] (0 = bands of rows), got " +
                std::to_string(schedule.tile));
  std::vector<Tile> tiles;
  if (schedule.tile > 0) {
    for (int y = 0; y < height; y += schedule.tile)
      for (int x = 0; x < width; x += schedule.tile)
        tiles.push_back({x, y, std::min(x + schedule.tile, width), std::min(y + schedule.tile, height)});
    return tiles;
  }
  return make_bands(width, height, static_cast<long long>(effective_threads(schedule)) * schedule.grain);
}

std::vector<Tile> make_bands(int width, int height, long long count) {
  const int bands = static_cast<int>(std::min<long long>(count, height));
  std::vector<Tile> tiles;
  for (int i = 0; i < bands; ++i)
    tiles.push_back({0, static_cast<int>(static_cast<long long>(height) * i / bands), width,
                     static_cast<int>(static_cast<long long>(height) * (i + 1) / bands)});
  return tiles;
}

FrameResult render_pass(const Renderer& renderer, const Schedule& schedule, Film& film,
                        int pass, const Progress& progress, std::stop_token stop) {
  const RenderSettings& st = renderer.settings();
  const std::vector<Tile> tiles = make_tiles(schedule, st.width, st.height);
  const int n = static_cast<int>(tiles.size());
  FrameResult result;
  result.portions = n;
  std::mutex mutex;
  int done = 0;
  std::atomic<bool> skipped = false;
  auto work = [&](int i) {
    if (stop.stop_requested()) {
      skipped = true;
      return;
    }
    RayCounts counts;
    renderer.render_tile(tiles[std::size_t(i)], pass, film, counts);
    const std::lock_guard<std::mutex> lock(mutex);
    result.rays += counts;
    ++done;
    if (progress) progress(done, n);
  };
  const int threads = effective_threads(schedule);
  const auto t0 = std::chrono::steady_clock::now();
  detail::run(schedule.backend, threads, n, work);
  result.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  result.complete = !skipped;
  return result;
}

FrameResult render_frame(const Renderer& renderer, const Schedule& schedule, Image& image,
                         const Progress& progress) {
  const RenderSettings& st = renderer.settings();
  check_image_fits(st.width, st.height);
  Film film(st.width, st.height);
  FrameResult result;
  const int passes = st.passes;
  for (int p = 0; p < passes; ++p) {
    const FrameResult r = render_pass(renderer, schedule, film, p, [&](int done, int total) {
      if (progress) progress(p * total + done, passes * total);
    });
    result.rays += r.rays;
    result.ms += r.ms;
    result.portions = r.portions;
  }
  result.nonfinite_pixels = film.resolve(image);
  return result;
}

}  // namespace rt2
