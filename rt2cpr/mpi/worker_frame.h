// rt2cpr/mpi/worker_frame.h — a worker's part of a frame (any rank but 0): it asks rank 0
// for tiles (protocol.h), renders them with its render threads and sends back their means.
#pragma once

#include "rt2cpr/mpi/frame_tally.h"
#include "rt2cpr/mpi/render_team.h"

namespace rt2cpr::mpi {

// Renders this rank's share of the frame with `team`, holding `credits` tiles (protocol.h),
// until rank 0 has ended each of its chains; returns its tally. The main thread sends each
// finished tile at once (it waits on the render threads' queue, at most kPoll while they
// render and kPollIdle while they wait, then polls for rank 0's answers). Throws rt2::Error
// for a message the protocol does not allow or a failing MPI call, and rethrows a failure
// of its render threads.
FrameTally render_worker_frame(RenderTeam& team, int credits);

}  // namespace rt2cpr::mpi
