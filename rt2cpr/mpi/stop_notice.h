// rt2cpr/mpi/stop_notice.h — rank 0's one line when mpirun ends the job from outside.
//
// When a process of the job dies (killed, taken by the OOM killer, crashed), Open MPI 4.1's
// mpirun ends the others: SIGCONT, a second later SIGTERM, and SIGKILL a second after that
// (orte/mca/odls/base: kill_local_procs). It offers no way to go on without the dead rank,
// nor to learn which rank it was (the fault-tolerant ULFM extension is not in Debian's
// build), and between processes of one machine no MPI call even fails. So rank 0 cannot
// finish the frame; on SIGTERM it says in one line why it stops, and nothing is written
// (outputs appear whole or not at all). mpirun names the rank that died in its own report,
// which `mpirun -q` leaves out.
#pragma once

namespace rt2cpr::mpi {

class StopNotice {
 public:
  // Installs rank 0's handler (`root`) or a worker's, unless SIGTERM is not at its default
  // (ignored or handled by someone else).
  //
  // The other ranks let rank 0 go first: mpirun's second between SIGTERM and SIGKILL is a
  // sleep that ends early when one of its processes exits, so a worker dying at once on
  // SIGTERM can cut it too short for rank 0's line. So a worker ignores a SIGTERM from its
  // parent (mpirun, or on another machine Open MPI's daemon) and ends with the SIGKILL that
  // follows rank 0's exit; a SIGTERM from anyone else ends it as usual.
  explicit StopNotice(bool root);
  ~StopNotice() { release(); }
  StopNotice(const StopNotice&) = delete;
  StopNotice& operator=(const StopNotice&) = delete;

  // SIGTERM back to its default: while the outputs are written, the handler of
  // rt2/image/output_file.h removes a half-written file instead.
  void release();

 private:
  bool installed_ = false;
};

}  // namespace rt2cpr::mpi
