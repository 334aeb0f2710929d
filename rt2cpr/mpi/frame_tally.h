// rt2cpr/mpi/frame_tally.h — one rank's part of one frame, exchanged by every rank at the
// frame's end (an MPI_Iallgather, which also keeps frames apart: protocol.h); rank 0 sums
// the rays for the report and keeps each rank's figures for --stats.
#pragma once

#include <cstdint>
#include <type_traits>

#include "rt2/render/renderer.h"

namespace rt2cpr::mpi {

struct FrameTally {
  rt2::RayCounts rays;
  std::uint64_t tiles = 0;             // tiles it rendered
  std::uint64_t bytes_sent = 0;        // payload of its point-to-point messages
  std::uint64_t nonfinite_pixels = 0;  // Film::resolve's count over its tiles
  double busy_ms = 0.0;   // its render threads' time in tiles, summed over the threads
  double serve_ms = 0.0;  // rank 0: its main thread's time handling messages

  FrameTally& operator+=(const FrameTally& o) {
    rays += o.rays;
    tiles += o.tiles;
    bytes_sent += o.bytes_sent;
    nonfinite_pixels += o.nonfinite_pixels;
    busy_ms += o.busy_ms;
    serve_ms += o.serve_ms;
    return *this;
  }
};
static_assert(std::is_trivially_copyable_v<FrameTally>);

}  // namespace rt2cpr::mpi
