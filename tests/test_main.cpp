// tests/test_main.cpp — main() of the test programs that run rt2 (rt2_tests, viewer_tests,
// mpi_tests): GoogleTest's, then oneTBB's worker threads joined before the program exits.
// Left to oneTBB's static destructor, the workers wind down while LeakSanitizer's exit-time
// check stops every thread, and that check then crashes now and then ("Tracer caught signal
// 11"), failing an ASan run whose tests all passed (google/sanitizers#1353).
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cstdio>
#include <new>

int main(int argc, char** argv) {
  tbb::task_scheduler_handle tbb_workers{tbb::attach{}};
  testing::InitGoogleTest(&argc, argv);
  const int status = RUN_ALL_TESTS();
  if (!tbb::finalize(tbb_workers, std::nothrow))
    std::fprintf(stderr, "test_main: oneTBB's worker threads were still in use at exit\n");
  return status;
}
