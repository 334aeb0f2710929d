// rt2cpr/mpi/calls.h — how rt2cpr_mpi calls MPI: every call's error code checked, waits
// that sleep instead of spinning, and the few message shapes it sends (bytes, text, one
// record from every rank).
//
// Open MPI's blocking calls (MPI_Recv, MPI_Wait, a blocking collective) poll in a busy loop
// until they complete: a process waiting for rank 0 would take a core from its own render
// threads, or from other ranks. So rt2cpr_mpi makes only non-blocking calls and waits by
// testing, sleeping between two tests: kPoll while its render threads are busy, kPollIdle
// while they wait for work (the message waited for is what they need), and on rank 0,
// whose answers every worker waits for, kPollServe while any worker is in the frame.
#pragma once

#include <mpi.h>

#include <chrono>
#include <cstddef>
#include <cstring>
#include <functional>
#include <string>
#include <type_traits>
#include <vector>

namespace rt2cpr::mpi {

// Each interval trades the CPU a wake-up costs against how late a message is seen; shorter
// ones slow ranks that share cores.
inline constexpr std::chrono::microseconds kPoll{1000}, kPollServe{500}, kPollIdle{200};

// Called while a wait finds its request pending (before each sleep); may throw to give up.
using Between = std::function<void()>;

// Throws rt2::Error "MPI_NAME failed: <the library's text>" unless `rc` is MPI_SUCCESS.
// MPI_COMM_WORLD returns its errors (MPI_ERRORS_RETURN, set by Session) instead of
// aborting inside the library, so that rank 0 can say what failed.
void check(int rc, const char* call);

// Waits for `request` to complete, calling `between` (when given) after each test that
// found it pending, then sleeping `poll` (kPollIdle: the waits between frames, when no
// thread renders).
void wait(MPI_Request& request, const Between& between = {},
          std::chrono::microseconds poll = kPollIdle);

// The message `probed` announced (MPI_Iprobe's status), received whole.
std::vector<std::byte> receive(const MPI_Status& probed);

// Sends `text` (its bytes, no terminator) to rank `dest` with `tag` and waits until it is out.
void send_text(int dest, int tag, const std::string& text);

// A message's bytes as text.
std::string text_of(const std::vector<std::byte>& bytes);

// Waits for a message of `tag` from `source` and returns its bytes as text.
std::string receive_text(int source, int tag);

// A trivially copyable value as bytes, and back (throws rt2::Error on a size mismatch:
// a message that is not what the protocol says).
template <class T>
std::vector<std::byte> bytes_of(const T& value) {
  static_assert(std::is_trivially_copyable_v<T>);
  const auto* p = reinterpret_cast<const std::byte*>(&value);
  return {p, p + sizeof(T)};
}
void check_size(std::size_t got, std::size_t expected);
template <class T>
T value_of(const std::vector<std::byte>& bytes) {
  static_assert(std::is_trivially_copyable_v<T>);
  check_size(bytes.size(), sizeof(T));
  T value;
  std::memcpy(&value, bytes.data(), sizeof(T));
  return value;
}

// Every rank's `mine`, in rank order, on every rank (MPI_Iallgather). It completes on no
// rank before every rank has called it.
template <class T>
std::vector<T> allgather(const T& mine, const Between& between = {}) {
  static_assert(std::is_trivially_copyable_v<T>);
  int size = 0;
  check(MPI_Comm_size(MPI_COMM_WORLD, &size), "MPI_Comm_size");
  std::vector<T> all(static_cast<std::size_t>(size));
  MPI_Request request;
  check(MPI_Iallgather(&mine, sizeof(T), MPI_BYTE, all.data(), sizeof(T), MPI_BYTE,
                       MPI_COMM_WORLD, &request),
        "MPI_Iallgather");
  wait(request, between);
  return all;
}

}  // namespace rt2cpr::mpi
