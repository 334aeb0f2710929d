// rt2/render/schedule.h — rendering a whole frame in parallel: serial, OpenMP or oneTBB.
//
// The frame is cut into tiles: by default `threads x grain` portions (bands of consecutive
// rows, sizes differing by at most one row; fewer when the image has fewer rows: the
// thesis's portions), or square tiles of `tile` pixels. Each tile is one call of
// Renderer::render_tile per pass. The backends are thin adapters that hand tiles to threads
// dynamically; because every pixel is computed independently, the image is bit-identical
// whatever the backend, thread count, grain, tile size or number of passes.
#pragma once

#include <cstdint>
#include <functional>
#include <stop_token>
#include <string>
#include <vector>

#include "rt2/render/renderer.h"

namespace rt2 {

enum class Backend { serial, omp, tbb };

struct Schedule {
  Backend backend = Backend::omp;
  int threads = 0;  // 0 = the number of hardware threads
  int grain = 4;    // portions of work per thread, >= 1 (thesis table 9)
  int tile = 0;     // 0: the portions are bands of rows; N > 0: N x N tiles (1 ... 65535)
};

const char* backend_name(Backend b);
// "serial" / "omp" / "tbb"; throws rt2::Error naming the value otherwise.
Backend parse_backend(const std::string& name);
// The thread count a schedule really uses (resolves 0; serial is 1).
int effective_threads(const Schedule& s);

struct FrameResult {
  RayCounts rays;
  double ms = 0.0;  // wall time
  int portions = 0;  // tiles
  // render_pass only: false when a stop request left some tiles unrendered (the film then
  // holds part of the pass and is only fit to be cleared).
  bool complete = true;
  std::uint64_t nonfinite_pixels = 0;  // render_frame only: see Film::resolve
};

// The schedule's tiles for a width x height image, row by row. Throws rt2::Error for
// threads < 0 or > 1024, grain < 1 or > 1'000'000, tile < 0 or > 65535.
std::vector<Tile> make_tiles(const Schedule& schedule, int width, int height);

// Called after each finished tile with (tiles done, tiles in all), from worker threads, one
// call at a time.
using Progress = std::function<void(int, int)>;

// Renders pass `pass` of every tile into `film` (which must be the settings' size). Once
// `stop` is requested, tiles not yet started are skipped (those being rendered finish) and
// the result is not `complete`: an interactive view drops a pass its camera left.
FrameResult render_pass(const Renderer& renderer, const Schedule& schedule, Film& film,
                        int pass, const Progress& progress = {}, std::stop_token stop = {});

// Renders every pass of the frame into a fresh film and its mean into `image` (resized to
// the settings' size); progress counts tiles over all passes.
FrameResult render_frame(const Renderer& renderer, const Schedule& schedule, Image& image,
                         const Progress& progress = {});

namespace detail {
// The backends, over portion indices [0, portions). Each calls work(i) exactly once per i.
void run_serial(int portions, const std::function<void(int)>& work);
void run_omp(int threads, int portions, const std::function<void(int)>& work);
void run_tbb(int threads, int portions, const std::function<void(int)>& work);
// The one `backend` names (serial ignores `threads`).
void run(Backend backend, int threads, int portions, const std::function<void(int)>& work);
}  // namespace detail

// `count` bands of whole rows over a width x height image (at most one per row), top to
// bottom, as even as rows allow: make_tiles' --tile 0.
std::vector<Tile> make_bands(int width, int height, long long count);

}  // namespace rt2
