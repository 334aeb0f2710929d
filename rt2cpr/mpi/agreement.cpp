// rt2cpr/mpi/agreement.cpp — failing together (see agreement.h).
#include "rt2cpr/mpi/agreement.h"

#include <algorithm>
#include <vector>

#include "rt2/base/error.h"
#include "rt2cpr/mpi/calls.h"
#include "rt2cpr/mpi/protocol.h"

namespace rt2cpr::mpi {

void agree(const Session& session, const std::optional<std::string>& failure) {
  const std::vector<int> failed = allgather<int>(failure.has_value());
  const auto first = std::find(failed.begin(), failed.end(), 1);
  if (first == failed.end()) return;
  const int culprit = static_cast<int>(first - failed.begin());
  if (session.root() && culprit == 0) throw rt2::Error(*failure);
  if (session.rank() == culprit) send_text(0, kFailure, session.name() + ": " + *failure);
  if (session.root()) throw rt2::Error(receive_text(culprit, kFailure));
  throw rt2::Error("the step failed on rank " + std::to_string(culprit));
}

}  // namespace rt2cpr::mpi
