// rt2cpr/mpi/agreement.h — a step every rank takes (reading the options, loading the scene
// ...) that fails on all of them when it fails on any: how bad input is reported once, and
// how a rank that cannot load the scene stops the job before it renders.
#pragma once

#include <optional>
#include <string>

#include "rt2cpr/mpi/session.h"

namespace rt2cpr::mpi {

// Every rank says whether its step failed (`failure`: its one-line message). When none
// did, returns on every rank. Otherwise throws rt2::Error on every rank: on rank 0 with the
// message of the lowest failing rank — its own as it is (a bad option or a missing file
// fails every rank alike: one line, as rt2cpr prints it), another's as "rank R (HOST):
// message" — and on the others with a message nobody prints. No rank returns or throws
// before every rank has finished the step.
void agree(const Session& session, const std::optional<std::string>& failure);

}  // namespace rt2cpr::mpi
