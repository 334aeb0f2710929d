// tests/mlib/dot_avx2_checks.cpp — mlib's dot product as the translation units built for
// AVX2 and AVX-512 compute it (simd.h: a multiply and two shuffle-adds), for
// vec4_ops_test.cpp to compare with the baseline's dpps, called only on a CPU that has
// AVX2. No library template here (see vfloat_checks.h).
#include "mlib/simd.h"

namespace mlib::test {

// out[4 i ... 4 i + 3] = dp_bcast of a[4 i ...] and b[4 i ...], for i < n.
void dot_avx2(const float* a, const float* b, float* out, int n) {
  for (int i = 0; i < n; ++i)
    simd::store(out + 4 * i, simd::dp_bcast(simd::load(a + 4 * i), simd::load(b + 4 * i)));
}

}  // namespace mlib::test
