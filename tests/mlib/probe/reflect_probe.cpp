// Compiled to assembly with the release flags by tests/SConscript; tests/mlib/asm_test.cpp
// counts the instructions. Two forms: operands in registers, and rt2's by-const-reference
// form.
#include "mlib/vec4_functions.h"

using mlib::vec4;

// simd::f4 is __m128 in the SSE build and a plain struct in the scalar one (MLIB_SCALAR).
extern "C" mlib::simd::f4 reflect_probe_regs(mlib::simd::f4 n_, mlib::simd::f4 i_) {
  const vec4 n(n_), i(i_);
  const vec4 r = i - 2.0f * n * dot(n, i);
  return r.m128();
}

extern "C" vec4 reflect_probe_refs(const vec4& n, const vec4& i) {
  return i - 2.0f * n * dot(n, i);
}
