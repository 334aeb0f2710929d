// mlib/fpmode.h — the calling thread's floating-point mode: flushing denormals to zero.
//
// Ray tracers run with FTZ (a result that would be denormal becomes 0) and DAZ (a denormal
// input is read as 0): on many x86 cores an operation on a denormal costs a microcode
// assist of ~100 cycles, and a grazing ray or a tiny triangle produces them. Embree sets
// both in its own threads and asks applications to set them in theirs. The mode lives in
// the MXCSR register, which is per thread: a program sets it in every thread that
// computes, e.g. at the start of each task a worker runs.
//
// Beside mlib/simd.h this is the only mlib file with intrinsics (MXCSR is thread state, not
// four-float arithmetic, so it is not part of the simd API that simd_scalar.h mirrors). It
// applies to the scalar build (arch=scalar) too: x86-64 does scalar float arithmetic in SSE
// registers, under the same MXCSR.
#pragma once

#include <pmmintrin.h>  // _MM_SET_DENORMALS_ZERO_MODE (the macro only reads and writes MXCSR)

namespace mlib {

// Whether the calling thread flushes denormals: both FTZ and DAZ are on.
inline bool flush_denormals() {
  return _MM_GET_FLUSH_ZERO_MODE() == _MM_FLUSH_ZERO_ON &&
         _MM_GET_DENORMALS_ZERO_MODE() == _MM_DENORMALS_ZERO_ON;
}

// Turns FTZ and DAZ on (or off) for the calling thread only; returns flush_denormals() as it
// was before, so that a caller can restore it.
inline bool set_flush_denormals(bool on = true) {
  const bool was = flush_denormals();
  _MM_SET_FLUSH_ZERO_MODE(on ? _MM_FLUSH_ZERO_ON : _MM_FLUSH_ZERO_OFF);
  _MM_SET_DENORMALS_ZERO_MODE(on ? _MM_DENORMALS_ZERO_ON : _MM_DENORMALS_ZERO_OFF);
  return was;
}

}  // namespace mlib
