// rt2cpr/mpi/protocol.h — the messages of a frame between rank 0 and the other ranks.
//
// Rank 0 hands the frame's tiles out one at a time, on demand (self-scheduling), and
// renders tiles itself between two messages (root_frame.h). A worker (worker_frame.h)
// opens the frame with one kRequest holding its credits c, the tiles it wants in hand
// (credits() below). Rank 0 answers each credit, and later each kResult, with one kTile (a
// tile to render, while any is left) or kDone: each of a worker's c chains (request -> tile
// -> result -> tile ...) ends in exactly one kDone, and the worker's frame is over after c
// of them. A collective at each frame's end (frame_tally.h) keeps frames apart. kError
// carries a worker's failure as text, which rank 0 prints before aborting the job.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "rt2/render/tile.h"

namespace rt2cpr::mpi {

enum Tag : int {
  kRequest = 1,  // worker -> 0: std::int32_t credits
  kTile,         // 0 -> worker: TileOrder
  kDone,         // 0 -> worker: no payload; one chain has ended
  kResult,       // worker -> 0: std::int32_t tile index, then the tile's pixels (3 floats each)
  kError,        // worker -> 0: text
  kFailure,      // agreement: the first failing rank's text to rank 0
};

// A tile to render: its index in the frame's list and its pixels.
struct TileOrder {
  std::int32_t index = 0;
  rt2::Tile tile;
};
static_assert(sizeof(TileOrder) == 20 && std::is_trivially_copyable_v<TileOrder>);

// The tiles a worker of `threads` render threads holds (rendering or queued), in a frame of
// `tiles` tiles over `all_threads` threads: enough that a thread finishing a tile finds the
// next one queued while the answer to its result is on its way (rank 0 notices the result
// within kPollServe, the worker the answer within kPoll: calls.h), but not so many that at
// the frame's end it holds much that another rank could have rendered sooner. Per thread:
// the one it renders, and one to three more as a 16th of its fair share of the frame
// allows (bands of rows, a few per thread: one more; 64-pixel tiles of the hard preset, 96
// per thread on 2 threads: three more). So a tile should take a few milliseconds or more.
inline int credits(int threads, std::size_t tiles, int all_threads) {
  const std::size_t fair = tiles / std::size_t(all_threads);
  return threads * (1 + static_cast<int>(std::clamp<std::size_t>(fair / 16, 1, 3)));
}

// The bytes of a kResult message for `tile`: its index, then its means.
inline std::size_t result_bytes(const rt2::Tile& tile) {
  return sizeof(std::int32_t) + tile.pixels() * 3 * sizeof(float);
}

}  // namespace rt2cpr::mpi
