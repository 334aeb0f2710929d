// rt2cpr/mpi/session.h — this process's place in the MPI job: MPI started and ended, its
// rank, the job's size, the name it is known by in messages.
//
// Threads: MPI_THREAD_FUNNELED. Only each process's main thread calls MPI; its render
// threads never do (they take tiles from a local queue, or on rank 0 from a counter shared
// with the main thread, and hand pixels back through a queue: render_team.h), so the main
// thread is free to serve messages while they render. A serving thread of its own under
// MPI_THREAD_MULTIPLE would buy nothing here: every call would take Open MPI's locks, and
// a thread blocked in MPI_Recv spins on a core the renderer needs (calls.h).
#pragma once

#include <string>

namespace rt2cpr::mpi {

class Session {
 public:
  // MPI_Init_thread; MPI_COMM_WORLD set to return errors (calls.h). Only rank 0 prints:
  // every other rank's standard output goes to /dev/null (its --help, its report), and
  // its failures reach rank 0 as messages. A library without MPI_THREAD_FUNNELED ends the
  // job with one line.
  Session(int& argc, char**& argv);
  // Waits (sleeping) until every rank has come here, so that ranks done early do not spin
  // while rank 0 writes the image, then MPI_Finalize.
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }
  const std::string& host() const { return host_; }
  // "rank R (HOST)": how rank 0's messages name this process.
  std::string name() const;
  // Ends every process of the job with `status` (MPI_Abort).
  [[noreturn]] void abort(int status) const;

 private:
  int rank_ = 0, size_ = 1;
  std::string host_;
};

}  // namespace rt2cpr::mpi
