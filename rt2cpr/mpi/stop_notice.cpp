// rt2cpr/mpi/stop_notice.cpp — rank 0's line on SIGTERM (see stop_notice.h).
#include "rt2cpr/mpi/stop_notice.h"

#include <unistd.h>

#include <csignal>

namespace rt2cpr::mpi {
namespace {

constexpr char kLine[] =
    "rt2cpr: the MPI job was ended by mpirun (SIGTERM): one of its processes died, or mpirun "
    "was interrupted; nothing was written\n";

// Async-signal-safe: write, signal and raise only.
extern "C" void on_sigterm(int sig) {
  [[maybe_unused]] const ssize_t n = ::write(STDERR_FILENO, kLine, sizeof kLine - 1);
  ::signal(sig, SIG_DFL);
  ::raise(sig);  // delivered when this handler returns: the default action ends the process
}

}  // namespace

StopNotice::StopNotice() {
  struct sigaction old {};
  if (::sigaction(SIGTERM, nullptr, &old) != 0 || old.sa_handler != SIG_DFL) return;
  struct sigaction sa {};
  sa.sa_handler = on_sigterm;
  sigemptyset(&sa.sa_mask);
  installed_ = ::sigaction(SIGTERM, &sa, nullptr) == 0;
}

void StopNotice::release() {
  if (!installed_) return;
  ::signal(SIGTERM, SIG_DFL);
  installed_ = false;
}

}  // namespace rt2cpr::mpi
