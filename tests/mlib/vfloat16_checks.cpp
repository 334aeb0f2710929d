// tests/mlib/vfloat16_checks.cpp — vfloat16's checks (vfloat_checks.h), compiled for AVX-512
// and called by vfloat_test.cpp only on a CPU that has it (nothing here runs at start-up).
#include "tests/mlib/vfloat_checks.h"

namespace mlib::test {

int check_vfloat16(char (&first)[kFirstFailureSize]) { return check_vfloat<vfloat16>(first); }
// vfloat8's compress_in_order in its AVX-512 form (the one this unit's flags select), and
// vfloat16's.
int check_compress_in_order_avx512(char (&first)[kFirstFailureSize]) {
  const int eight = check_compress_in_order<vfloat8>(first);
  return eight ? eight : check_compress_in_order<vfloat16>(first);
}

}  // namespace mlib::test
