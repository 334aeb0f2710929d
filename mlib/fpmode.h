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

// The calling thread's FTZ and DAZ bits (as MXCSR holds them), for other threads to adopt.
inline unsigned denormal_mode() {
  return _MM_GET_FLUSH_ZERO_MODE() | _MM_GET_DENORMALS_ZERO_MODE();
}

// Sets the calling thread's FTZ and DAZ bits to those of `mode` (denormal_mode()); returns
// the bits it had.
inline unsigned set_denormal_mode(unsigned mode) {
  const unsigned was = denormal_mode();
  _MM_SET_FLUSH_ZERO_MODE(mode & _MM_FLUSH_ZERO_MASK);
  _MM_SET_DENORMALS_ZERO_MODE(mode & _MM_DENORMALS_ZERO_MASK);
  return was;
}

// Holds the calling thread at `mode` (denormal_mode()) while it lives, then restores the
// thread's own. Made at the start of a parallel region with the mode of the thread that
// opened it, every thread of the team computes as that thread would alone.
class DenormalModeScope {
 public:
  explicit DenormalModeScope(unsigned mode) : was_(set_denormal_mode(mode)) {}
  ~DenormalModeScope() { set_denormal_mode(was_); }
  DenormalModeScope(const DenormalModeScope&) = delete;
  DenormalModeScope& operator=(const DenormalModeScope&) = delete;

 private:
  unsigned was_;
};

}  // namespace mlib
