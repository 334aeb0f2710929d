// rt2cpr/mpi/worker_frame.cpp — asking for tiles, rendering them, sending them back (see
// worker_frame.h).
#include "rt2cpr/mpi/worker_frame.h"

#include <cstring>

#include "rt2/base/error.h"
#include "rt2cpr/mpi/channel.h"
#include "rt2cpr/mpi/protocol.h"
#include "rt2cpr/mpi/sender.h"

namespace rt2cpr::mpi {
namespace {

struct Finished {
  std::int32_t index;
  std::vector<float> rgb;
};

// A kResult message: the tile's index, then its means.
std::vector<std::byte> result_message(const Finished& f) {
  std::vector<std::byte> bytes(sizeof f.index + f.rgb.size() * sizeof(float));
  std::memcpy(bytes.data(), &f.index, sizeof f.index);
  std::memcpy(bytes.data() + sizeof f.index, f.rgb.data(), f.rgb.size() * sizeof(float));
  return bytes;
}

}  // namespace

FrameTally render_worker_frame(RenderTeam& team, int credits) {
  Channel<TileOrder> orders;
  Channel<Finished> finished;
  team.start([&] { return orders.pop(); },
             [&](const TileOrder& order, std::vector<float>&& rgb) {
               finished.push({order.index, std::move(rgb)});
             });
  // However this function ends, the loops waiting for an order are released, and done
  // with the channels before they go.
  struct Release {
    Channel<TileOrder>& orders;
    RenderTeam& team;
    ~Release() {
      orders.close();
      team.stop();
    }
  } release{orders, team};

  Sender sender;
  sender.send(0, kRequest, bytes_of(std::int32_t{credits}));
  int open = credits;
  while (open > 0) {
    if (team.failed()) {
      orders.close();
      team.finish();  // rethrows
    }
    bool busy = false;
    while (std::optional<Finished> f = finished.try_pop()) {
      sender.send(0, kResult, result_message(*f));
      busy = true;
    }
    int found = 0;
    MPI_Status st;
    check(MPI_Iprobe(0, MPI_ANY_TAG, MPI_COMM_WORLD, &found, &st), "MPI_Iprobe");
    if (found) {
      busy = true;
      const std::vector<std::byte> bytes = receive(st);
      if (st.MPI_TAG == kTile) {
        orders.push(value_of<TileOrder>(bytes));
      } else if (st.MPI_TAG == kDone) {
        --open;
      } else {
        throw rt2::Error("MPI protocol: an unexpected message from rank 0 (tag " +
                         std::to_string(st.MPI_TAG) + ")");
      }
    }
    sender.reap();
    if (!busy) finished.wait_for(team.rendering() ? kPoll : kPollIdle);  // or a tile is done
  }
  orders.close();
  FrameTally tally = team.finish();
  sender.drain();
  tally.bytes_sent = sender.bytes_sent();
  return tally;
}

}  // namespace rt2cpr::mpi
