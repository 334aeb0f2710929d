// rt2cpr/mpi/root_frame.h — rank 0's part of a frame: it hands the tiles out (protocol.h),
// renders its own share with its render threads meanwhile, and puts every tile's pixels
// into the image.
#pragma once

#include <functional>
#include <vector>

#include "rt2/image/image.h"
#include "rt2cpr/mpi/calls.h"
#include "rt2cpr/mpi/frame_tally.h"
#include "rt2cpr/mpi/render_team.h"

namespace rt2cpr::mpi {

struct RootFrame {
  RenderTeam* team;                   // rank 0's threads; none: it only hands tiles out
  const std::vector<rt2::Tile>& tiles;
  int chains = 0;                     // the workers' credits, summed (protocol.h)
  rt2::Image& image;                  // the frame's size; every pixel is written
  std::function<void(int, int)> progress;  // (tiles in, tiles in all), from this thread
};

// Renders the frame with every rank; returns rank 0's own tally. Its render threads (unless
// it only serves) take tiles from the same counter the main thread hands out from, with no
// message. The main thread polls for messages (calls.h: kPollServe while a worker is in
// the frame, else kPoll while its threads render); throws rt2::Error for a worker's kError
// (its text), a message the protocol does not allow, or a failing MPI call, and rethrows a
// failure of its own render threads.
FrameTally render_root_frame(const RootFrame& frame);

}  // namespace rt2cpr::mpi
