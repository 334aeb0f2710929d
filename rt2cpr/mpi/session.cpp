// rt2cpr/mpi/session.cpp — MPI's start and end (see session.h).
#include "rt2cpr/mpi/session.h"

#include <mpi.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>

#include "rt2cpr/mpi/calls.h"

namespace rt2cpr::mpi {

Session::Session(int& argc, char**& argv) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);  // fails inside the library
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  char host[256] = {};
  host_ = ::gethostname(host, sizeof host - 1) == 0 ? host : "unknown host";
  if (rank_ != 0 && !std::freopen("/dev/null", "w", stdout)) std::fclose(stdout);
  if (provided < MPI_THREAD_FUNNELED) {
    if (rank_ == 0)
      std::fprintf(stderr, "rt2cpr: this MPI library does not support MPI_THREAD_FUNNELED\n");
    abort(1);
  }
}

Session::~Session() {
  try {
    MPI_Request request;
    check(MPI_Ibarrier(MPI_COMM_WORLD, &request), "MPI_Ibarrier");
    wait(request, {}, kPoll);  // rank 0 may be writing a large image meanwhile
  } catch (...) {
    // MPI_Finalize below reports what is wrong with the job, if anything.
  }
  MPI_Finalize();
}

std::string Session::name() const { return "rank " + std::to_string(rank_) + " (" + host_ + ")"; }

void Session::abort(int status) const {
  std::fflush(stdout);
  MPI_Abort(MPI_COMM_WORLD, status);
  std::_Exit(status);  // MPI_Abort does not return; this says so to the compiler
}

}  // namespace rt2cpr::mpi
