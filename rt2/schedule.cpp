// rt2/schedule.cpp — frame splitting, the serial and OpenMP backends.
#include "rt2/schedule.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <mutex>
#include <thread>

#include "rt2/error.h"

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

}  // namespace detail

FrameResult render_frame(const Renderer& renderer, const Schedule& schedule, Image& image,
                         const Progress& progress) {
  if (schedule.threads < 0 || schedule.threads > 1024)
    throw Error("threads must be in [1, 1024] (0 = all hardware threads), got " +
                std::to_string(schedule.threads));
  if (schedule.grain < 1 || schedule.grain > 1'000'000)
    throw Error("grain must be in [1, 1000000], got " + std::to_string(schedule.grain));
  const RenderSettings& st = renderer.settings();
  if (image.width != st.width || image.height != st.height) {
    check_image_fits(st.width, st.height);
    image = Image(st.width, st.height);
  }

  const int threads = effective_threads(schedule);
  const long long wanted = static_cast<long long>(threads) * schedule.grain;
  const int portions = static_cast<int>(std::min<long long>(wanted, st.height));
  FrameResult result;
  result.portions = portions;
  std::mutex mutex;
  int done = 0;
  auto work = [&](int i) {
    const int y0 = static_cast<int>(static_cast<long long>(st.height) * i / portions);
    const int y1 = static_cast<int>(static_cast<long long>(st.height) * (i + 1) / portions);
    RayCounts counts;
    renderer.render_rows(y0, y1, image, counts);
    const std::lock_guard<std::mutex> lock(mutex);
    result.rays += counts;
    ++done;
    if (progress) progress(done, portions);
  };
  const auto t0 = std::chrono::steady_clock::now();
  switch (schedule.backend) {
    case Backend::serial: detail::run_serial(portions, work); break;
    case Backend::omp: detail::run_omp(threads, portions, work); break;
    case Backend::tbb: detail::run_tbb(threads, portions, work); break;
  }
  result.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace rt2
