// tests/mlib/vfloat8_checks.cpp — vfloat8's checks (vfloat_checks.h), and its AVX2
// compress_in_order, compiled for AVX2 and
// called by vfloat_test.cpp only on a CPU that has it (nothing here runs at start-up).
#include "tests/mlib/vfloat_checks.h"

namespace mlib::test {

int check_vfloat8(char (&first)[kFirstFailureSize]) { return check_vfloat<vfloat8>(first); }
int check_compress_in_order_avx2(char (&first)[kFirstFailureSize]) {
  return check_compress_in_order<vfloat8>(first);
}

}  // namespace mlib::test
