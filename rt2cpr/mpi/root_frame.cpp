// rt2cpr/mpi/root_frame.cpp — serving tiles while rendering (see root_frame.h).
#include "rt2cpr/mpi/root_frame.h"

#include <atomic>
#include <cstring>
#include <optional>
#include <thread>

#include "rt2/base/error.h"
#include "rt2cpr/clock.h"
#include "rt2cpr/mpi/protocol.h"
#include "rt2cpr/mpi/sender.h"

namespace rt2cpr::mpi {
namespace {

// A tile's means (row by row) into its place in the image.
void paste(rt2::Image& image, const rt2::Tile& tile, const float* rgb) {
  const std::size_t row = std::size_t(tile.width()) * 3;
  for (int y = tile.y0; y < tile.y1; ++y, rgb += row)
    std::memcpy(image.row(y) + std::size_t(tile.x0) * 3, rgb, row * sizeof(float));
}

[[noreturn]] void protocol_error(const MPI_Status& st, const std::string& what) {
  throw rt2::Error("MPI protocol: " + what + " from rank " + std::to_string(st.MPI_SOURCE) +
                   " (tag " + std::to_string(st.MPI_TAG) + ")");
}

}  // namespace

FrameTally render_root_frame(const RootFrame& frame) {
  const int n = static_cast<int>(frame.tiles.size());
  std::atomic<int> next = 0, in = 0;
  const auto take = [&]() -> std::optional<TileOrder> {
    const int i = next.fetch_add(1);
    if (i >= n) return std::nullopt;
    return TileOrder{i, frame.tiles[std::size_t(i)]};
  };
  RenderTeam* const team = frame.team;
  if (team)
    team->start(take, [&](const TileOrder& order, std::vector<float>&& rgb) {
      paste(frame.image, order.tile, rgb.data());
      ++in;
    });
  // However this function ends, the loops are done with its counters before they go.
  struct Stop {
    RenderTeam* team;
    ~Stop() {
      if (team) team->stop();
    }
  } stop{team};

  Sender sender;
  std::vector<int> holder(std::size_t(n), -1);  // the worker a tile is out with
  int open = frame.chains;
  // One answer to a worker's credit or result: its next tile, or the end of that chain.
  const auto answer = [&](int worker) {
    if (const std::optional<TileOrder> order = take()) {
      holder[std::size_t(order->index)] = worker;
      sender.send(worker, kTile, bytes_of(*order));
    } else {
      sender.send(worker, kDone, {});
      --open;
    }
  };
  double serve_ms = 0.0;
  while (in < n || open > 0) {
    if (team && team->failed()) team->finish();  // rethrows
    int found = 0;
    MPI_Status st;
    check(MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &found, &st), "MPI_Iprobe");
    if (!found) {
      sender.reap();
      if (frame.progress) frame.progress(in, n);
      std::this_thread::sleep_for(open > 0 ? kPollServe
                                  : team && team->rendering() ? kPoll : kPollIdle);
      continue;
    }
    const auto t0 = Clock::now();
    const std::vector<std::byte> bytes = receive(st);
    switch (st.MPI_TAG) {
      case kRequest: {
        const auto wanted = value_of<std::int32_t>(bytes);
        if (wanted < 1 || wanted > open)
          protocol_error(st, "a request for " + std::to_string(wanted) + " tiles");
        for (int k = 0; k < wanted; ++k) answer(st.MPI_SOURCE);
        break;
      }
      case kResult: {
        std::int32_t index = -1;
        if (bytes.size() >= sizeof index) std::memcpy(&index, bytes.data(), sizeof index);
        if (index < 0 || index >= n || holder[std::size_t(index)] != st.MPI_SOURCE)
          protocol_error(st, "a result for tile " + std::to_string(index) + " it does not hold");
        const rt2::Tile& tile = frame.tiles[std::size_t(index)];
        if (bytes.size() != result_bytes(tile)) protocol_error(st, "a result of the wrong size");
        paste(frame.image, tile, reinterpret_cast<const float*>(bytes.data() + sizeof index));
        holder[std::size_t(index)] = -1;
        ++in;
        answer(st.MPI_SOURCE);
        break;
      }
      case kError:
        throw rt2::Error(text_of(bytes));
      default:
        protocol_error(st, "an unexpected message");
    }
    serve_ms += ms_since(t0);
  }
  if (frame.progress) frame.progress(n, n);
  FrameTally tally = team ? team->finish() : FrameTally{};
  sender.drain();
  tally.bytes_sent = sender.bytes_sent();
  tally.serve_ms = serve_ms;
  return tally;
}

}  // namespace rt2cpr::mpi
