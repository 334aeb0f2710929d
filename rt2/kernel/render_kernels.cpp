// rt2/kernel/render_kernels.cpp — the renderer's table (render/kernel_table.h) for the
// instruction set this copy is compiled for.
#include "rt2/kernel/kernel.h"

#include "rt2/kernel/render_block.h"
#include "rt2/render/kernel_table.h"

namespace rt2::RT2_ISA {

const RenderKernels& render_kernels() {
  static const RenderKernels table{kIsa, {&render_tile<false>, &render_tile<true>}};
  return table;
}

}  // namespace rt2::RT2_ISA
