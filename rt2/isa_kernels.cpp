// rt2/isa_kernels.cpp — the per-instruction-set translation unit: the build compiles it
// once per set, with -DRT2_ISA=<name> and that set's flags, and nothing else gets those
// flags (rt2/isa.h). Everything defined here is in rt2::RT2_ISA.
#include "rt2/isa_kernels.h"

#include "rt2/tracer.h"

namespace rt2::RT2_ISA {

namespace {

template <bool Watertight>
void trace_closest(const Accel& acc, const Ray* rays, const float* t_max, std::size_t n,
                   Hit* hits, TraversalCounts* counts) {
  for (std::size_t i = 0; i < n; ++i)
    hits[i] = closest_hit<Watertight>(acc, rays[i], 0.0f, t_max[i], counts);
}

template <bool Watertight>
void trace_occluded(const Accel& acc, const Ray* rays, const float* t_max, std::size_t n,
                    std::uint8_t* occluded_out, TraversalCounts* counts) {
  for (std::size_t i = 0; i < n; ++i)
    occluded_out[i] = occluded<Watertight>(acc, rays[i], 0.0f, t_max[i], counts) ? 1 : 0;
}

}  // namespace

const IsaKernels& kernels() {
  static const IsaKernels table{
      Isa::RT2_ISA,  // the namespaces are named as the enumerators
      {&render_tile_kernel<false>, &render_tile_kernel<true>},
      {&trace_closest<false>, &trace_closest<true>},
      {&trace_occluded<false>, &trace_occluded<true>},
  };
  return table;
}

}  // namespace rt2::RT2_ISA
