// rt2cpr/mpi/sender.cpp — sends in flight (see sender.h).
#include "rt2cpr/mpi/sender.h"

#include <algorithm>

namespace rt2cpr::mpi {

Sender::~Sender() {
  for (Pending& p : pending_)
    if (p.request != MPI_REQUEST_NULL) MPI_Request_free(&p.request);
}

void Sender::send(int dest, int tag, std::vector<std::byte> bytes) {
  Pending p{std::move(bytes), MPI_REQUEST_NULL};
  check(MPI_Isend(p.bytes.data(), static_cast<int>(p.bytes.size()), MPI_BYTE, dest, tag,
                  MPI_COMM_WORLD, &p.request),
        "MPI_Isend");
  bytes_sent_ += p.bytes.size();
  pending_.push_back(std::move(p));  // the vector's buffer stays where MPI reads it
}

void Sender::reap() {
  std::erase_if(pending_, [](Pending& p) {
    int done = 0;
    check(MPI_Test(&p.request, &done, MPI_STATUS_IGNORE), "MPI_Test");
    return done != 0;
  });
}

void Sender::drain() {
  for (Pending& p : pending_) wait(p.request);
  pending_.clear();
}

}  // namespace rt2cpr::mpi
