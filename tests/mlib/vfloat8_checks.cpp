// tests/mlib/vfloat8_checks.cpp — vfloat8's checks (vfloat_checks.h), compiled for AVX2 and
// called by vfloat_test.cpp only on a CPU that has it (nothing here runs at start-up).
#include "tests/mlib/vfloat_checks.h"

namespace mlib::test {

int check_vfloat8(char (&first)[kFirstFailureSize]) { return check_vfloat<vfloat8>(first); }

}  // namespace mlib::test
