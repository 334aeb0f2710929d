// rt2cpr/mpi/protocol.h — the messages of a frame between rank 0 and the other ranks.
//
// Rank 0 hands the frame's tiles out one at a time, on demand (self-scheduling), and
// renders tiles itself between two messages (root_frame.h). A worker (worker_frame.h)
// opens the frame with one kRequest holding its credits c: the tiles it wants in hand.
// Rank 0 answers each credit, and later each kResult, with one kTile (a tile to render,
// while any is left) or kDone. So each of a worker's c chains request -> tile -> result ->
// tile ... ends in exactly one kDone: the worker's frame is over when it has received c of
// them, and rank 0's when every tile's pixels are in and every chain has ended. A
// collective at each frame's end (frame_tally.h) keeps frames apart: no request of the
// next frame reaches rank 0 before it has left this one. kError carries a worker's failure
// as text; rank 0 prints it and aborts the job. kFailure is the agreement's (agreement.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "rt2/tile.h"

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

// A worker keeps two tiles per render thread in hand: when a thread finishes one, the next
// is already queued while the answer to its result travels (a round trip of up to two
// kPoll, calls.h), and at a frame's end a worker holds at most one tile per thread that
// another rank could have rendered sooner.
inline int credits(int threads) { return 2 * threads; }

// The bytes of a kResult message for `tile`: its index, then its means.
inline std::size_t result_bytes(const rt2::Tile& tile) {
  return sizeof(std::int32_t) + tile.pixels() * 3 * sizeof(float);
}

}  // namespace rt2cpr::mpi
