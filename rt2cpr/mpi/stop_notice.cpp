// rt2cpr/mpi/stop_notice.cpp — SIGTERM in an MPI job (see stop_notice.h).
#include "rt2cpr/mpi/stop_notice.h"

#include <unistd.h>

#include <csignal>

namespace rt2cpr::mpi {
namespace {

constexpr char kLine[] =
    "rt2cpr: the MPI job was ended by mpirun (SIGTERM): one of its processes died, or mpirun "
    "was interrupted; nothing was written\n";

// The handlers are async-signal-safe: write, getppid, signal and raise only.
void die_of(int sig) {
  ::signal(sig, SIG_DFL);
  ::raise(sig);  // delivered when the handler returns: the default action ends the process
}

extern "C" void on_sigterm_root(int sig) {
  [[maybe_unused]] const ssize_t n = ::write(STDERR_FILENO, kLine, sizeof kLine - 1);
  die_of(sig);
}

extern "C" void on_sigterm_worker(int sig, siginfo_t* info, void*) {
  if (info->si_code == SI_USER && info->si_pid == ::getppid()) return;  // mpirun's: wait
  die_of(sig);
}

}  // namespace

StopNotice::StopNotice(bool root) {
  struct sigaction old {};
  if (::sigaction(SIGTERM, nullptr, &old) != 0 || old.sa_handler != SIG_DFL) return;
  struct sigaction sa {};
  if (root) {
    sa.sa_handler = on_sigterm_root;
  } else {
    sa.sa_sigaction = on_sigterm_worker;
    sa.sa_flags = SA_SIGINFO;
  }
  sigemptyset(&sa.sa_mask);
  installed_ = ::sigaction(SIGTERM, &sa, nullptr) == 0;
}

void StopNotice::release() {
  if (!installed_) return;
  ::signal(SIGTERM, SIG_DFL);
  installed_ = false;
}

}  // namespace rt2cpr::mpi
