// rt2/schedule.h — rendering a whole frame in parallel: serial, OpenMP or oneTBB.
//
// The frame's rows are cut into `threads x grain` portions (bands of consecutive rows,
// sizes differing by at most one row; fewer when the image has fewer rows), and each
// portion is one call of Renderer::render_rows. The backends are thin adapters that hand
// portions to threads dynamically; because every pixel is computed independently, the
// image is bit-identical whatever the backend, thread count or grain.
#pragma once

#include <functional>
#include <string>

#include "rt2/render.h"

namespace rt2 {

enum class Backend { serial, omp, tbb };

struct Schedule {
  Backend backend = Backend::omp;
  int threads = 0;  // 0 = the number of hardware threads
  int grain = 4;    // portions of work per thread, >= 1 (thesis table 9)
};

const char* backend_name(Backend b);
// "serial" / "omp" / "tbb"; throws rt2::Error naming the value otherwise.
Backend parse_backend(const std::string& name);
// The thread count a schedule really uses (resolves 0; serial is 1).
int effective_threads(const Schedule& s);

struct FrameResult {
  RayCounts rays;
  double ms = 0.0;  // wall time of the frame
  int portions = 0;
};

// Called after each finished portion with (portions done, portions in all), from worker
// threads, one call at a time.
using Progress = std::function<void(int, int)>;

// Renders the whole frame into `image` (resized to the settings' size). Throws rt2::Error
// for threads < 0 or > 1024, grain < 1 or > 1'000'000.
FrameResult render_frame(const Renderer& renderer, const Schedule& schedule, Image& image,
                         const Progress& progress = {});

namespace detail {
// The backends, over portion indices [0, portions). Each calls work(i) exactly once per i.
void run_serial(int portions, const std::function<void(int)>& work);
void run_omp(int threads, int portions, const std::function<void(int)>& work);
void run_tbb(int threads, int portions, const std::function<void(int)>& work);
}  // namespace detail

}  // namespace rt2
