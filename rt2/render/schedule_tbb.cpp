// rt2/render/schedule_tbb.cpp — the oneTBB backend: a task arena of the requested size and a
// parallel_for over portions with a simple partitioner (one portion per task). TBB limits
// its workers to the hardware threads unless a global_control allows more, so a request
// for 64 threads on 2 cores gets them, as it does with OpenMP.
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include "rt2/render/schedule.h"

namespace rt2::detail {

void run_tbb(int threads, int portions, const std::function<void(int)>& work) {
  tbb::global_control allow(tbb::global_control::max_allowed_parallelism,
                           static_cast<std::size_t>(threads));
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<int>(0, portions, 1),
        [&](const tbb::blocked_range<int>& range) {
          for (int i = range.begin(); i != range.end(); ++i) work(i);
        },
        tbb::simple_partitioner());
  });
}

}  // namespace rt2::detail
