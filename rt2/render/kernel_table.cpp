// rt2/render/kernel_table.cpp — the tables each copy of rt2/kernel/ defines in its
// namespace, looked up by instruction set.
#include "rt2/render/kernel_table.h"

#include "rt2/base/error.h"
#include "rt2/render/trace_kernels.h"

#if defined(MLIB_SCALAR)
namespace rt2::scalar {
const RenderKernels& render_kernels();
const TraceKernels& trace_kernels();
}  // namespace rt2::scalar
#else
namespace rt2::sse41 {
const RenderKernels& render_kernels();
const TraceKernels& trace_kernels();
}  // namespace rt2::sse41
namespace rt2::avx2 {
const RenderKernels& render_kernels();
const TraceKernels& trace_kernels();
}  // namespace rt2::avx2
namespace rt2::avx512 {
const RenderKernels& render_kernels();
const TraceKernels& trace_kernels();
}  // namespace rt2::avx512
#endif

namespace rt2 {
namespace {

// tables(sse41, avx2, avx512) for `isa`, or tables(scalar) in the scalar build.
template <class Table>
const Table& of_isa(Isa isa, const Table& (*sse41_or_scalar)(), const Table& (*avx2)(),
                    const Table& (*avx512)()) {
  for (Isa built : built_isas()) {
    if (built != isa) continue;
    return isa == Isa::avx512 ? avx512() : isa == Isa::avx2 ? avx2() : sse41_or_scalar();
  }
  throw Error(std::string("ISA '") + isa_name(isa) + "' is not in this build");
}

}  // namespace

#if defined(MLIB_SCALAR)
const RenderKernels& render_kernels(Isa isa) {
  return of_isa(isa, &scalar::render_kernels, &scalar::render_kernels, &scalar::render_kernels);
}
const TraceKernels& trace_kernels(Isa isa) {
  return of_isa(isa, &scalar::trace_kernels, &scalar::trace_kernels, &scalar::trace_kernels);
}
#else
const RenderKernels& render_kernels(Isa isa) {
  return of_isa(isa, &sse41::render_kernels, &avx2::render_kernels, &avx512::render_kernels);
}
const TraceKernels& trace_kernels(Isa isa) {
  return of_isa(isa, &sse41::trace_kernels, &avx2::trace_kernels, &avx512::trace_kernels);
}
#endif

}  // namespace rt2
