// rt2cpr/mpi/stop_notice.h — rank 0's one line when mpirun ends the job from outside.
//
// When a process of the job dies (killed, taken by the OOM killer, crashed), Open MPI 4.1's
// mpirun ends the others: SIGTERM, then SIGKILL a moment later. It offers no way to go on
// without the dead rank, nor to learn which rank it was (the fault-tolerant ULFM extension
// is not in Debian's build), and between processes of one machine no MPI call even fails.
// So rank 0 cannot finish the frame; on SIGTERM it says in one line why it stops, and
// nothing is written (outputs appear whole or not at all). mpirun names the rank that died
// in its own report, which `mpirun -q` leaves out.
#pragma once

namespace rt2cpr::mpi {

class StopNotice {
 public:
  // Installs the handler, unless SIGTERM is not at its default (ignored or handled by
  // someone else).
  StopNotice();
  ~StopNotice() { release(); }
  StopNotice(const StopNotice&) = delete;
  StopNotice& operator=(const StopNotice&) = delete;

  // SIGTERM back to its default: while the outputs are written, the handler of
  // rt2/io/output_file.h removes a half-written file instead.
  void release();

 private:
  bool installed_ = false;
};

}  // namespace rt2cpr::mpi
