// rt2cpr/mpi/calls.cpp — checked calls, sleeping waits, messages (see calls.h).
#include "rt2cpr/mpi/calls.h"

#include <thread>

#include "rt2/base/error.h"

namespace rt2cpr::mpi {

void check(int rc, const char* call) {
  if (rc == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  if (MPI_Error_string(rc, text, &length) != MPI_SUCCESS) length = 0;
  throw rt2::Error(std::string(call) + " failed: " +
                   (length > 0 ? std::string(text, std::size_t(length))
                               : "error " + std::to_string(rc)));
}

void check_size(std::size_t got, std::size_t expected) {
  if (got != expected)
    throw rt2::Error("MPI message of " + std::to_string(got) + " bytes where " +
                     std::to_string(expected) + " were expected");
}

void wait(MPI_Request& request, const Between& between, std::chrono::microseconds poll) {
  for (;;) {
    int done = 0;
    check(MPI_Test(&request, &done, MPI_STATUS_IGNORE), "MPI_Test");
    if (done) return;
    if (between) between();
    std::this_thread::sleep_for(poll);
  }
}

void send_text(int dest, int tag, const std::string& text) {
  MPI_Request request;
  check(MPI_Isend(text.data(), static_cast<int>(text.size()), MPI_BYTE, dest, tag,
                  MPI_COMM_WORLD, &request),
        "MPI_Isend");
  wait(request);
}

std::vector<std::byte> receive(const MPI_Status& probed) {
  int count = 0;
  check(MPI_Get_count(&probed, MPI_BYTE, &count), "MPI_Get_count");
  std::vector<std::byte> bytes(static_cast<std::size_t>(count));
  check(MPI_Recv(bytes.data(), count, MPI_BYTE, probed.MPI_SOURCE, probed.MPI_TAG,
                 MPI_COMM_WORLD, MPI_STATUS_IGNORE),
        "MPI_Recv");
  return bytes;
}

std::string text_of(const std::vector<std::byte>& bytes) {
  return std::string(reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

std::string receive_text(int source, int tag) {
  for (;;) {
    int found = 0;
    MPI_Status status;
    check(MPI_Iprobe(source, tag, MPI_COMM_WORLD, &found, &status), "MPI_Iprobe");
    if (found) return text_of(receive(status));
    std::this_thread::sleep_for(kPollIdle);
  }
}

}  // namespace rt2cpr::mpi
