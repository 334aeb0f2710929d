// rt2cpr/mpi/sender.h — messages on their way out: each one's bytes kept until MPI has
// sent them, and the payload bytes counted (--stats' bytes_sent).
#pragma once

#include <mpi.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "rt2cpr/mpi/calls.h"

namespace rt2cpr::mpi {

class Sender {
 public:
  Sender() = default;
  // Sends still pending are left to MPI (MPI_Request_free): only a failing job gets here
  // with any, and it is about to end.
  ~Sender();
  Sender(const Sender&) = delete;
  Sender& operator=(const Sender&) = delete;

  // Starts sending `bytes` to rank `dest` with `tag` (MPI_Isend).
  void send(int dest, int tag, std::vector<std::byte> bytes);
  // Forgets the sends that are complete.
  void reap();
  // Waits until every send is complete.
  void drain();
  std::uint64_t bytes_sent() const { return bytes_sent_; }

 private:
  struct Pending {
    std::vector<std::byte> bytes;
    MPI_Request request;
  };
  std::vector<Pending> pending_;
  std::uint64_t bytes_sent_ = 0;
};

}  // namespace rt2cpr::mpi
