// mlib/fpmode.h — the calling thread's floating-point mode: flushing denormals to zero.
//
// Ray tracers run with FTZ (a result that would be denormal becomes 0) and DAZ (a denormal
// input is read as 0): on many x86 cores an operation on a denormal takes a microcode
// assist, and grazing rays and tiny triangles produce them. Embree sets both in its threads
// and asks applications to do the same. The mode lives in MXCSR, which is per thread: set
// it in every thread that computes, e.g. at the start of each task a worker runs. Beside
// mlib/simd.h the only mlib file with intrinsics (MXCSR is thread state, not part of the
// simd API that simd_scalar.h mirrors); it applies to arch=scalar too, whose scalar float
// arithmetic runs in SSE registers under the same MXCSR.
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
