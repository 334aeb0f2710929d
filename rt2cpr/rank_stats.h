// rt2cpr/rank_stats.h — what one process of an MPI job (rt2cpr_mpi) did over all frames,
// as the report prints it and --stats writes it.
#pragma once

#include <cstdint>
#include <string>

namespace rt2cpr {

struct RankStats {
  int rank = 0;
  std::string host;
  int threads = 0;               // its render threads
  std::uint64_t tiles = 0;       // tiles it rendered
  std::uint64_t bytes_sent = 0;  // payload of its messages: requests and pixels, or tile orders
  double busy_ms = 0.0;          // its render threads' time in tiles, summed over the threads
  double serve_ms = 0.0;         // rank 0: its main thread's time handling messages
};

}  // namespace rt2cpr
