// rt2/kernels.cpp — explicit instantiations of the render kernel. The build compiles this
// file once per group with RT2_KERNEL_GROUP = g; group g holds feature sets 8g .. 8g+7, so
// the specialisations compile in parallel. Groups 8..11 (watertight without triangles) are
// not built: normalize_features maps those sets onto groups 0..3.
#include "rt2/tracer.h"

#ifndef RT2_KERNEL_GROUP
#error "compile with -DRT2_KERNEL_GROUP=<0..15>"
#endif

namespace rt2 {

constexpr unsigned kGroup = RT2_KERNEL_GROUP * 8u;
static_assert(normalize_features(kGroup) == kGroup && normalize_features(kGroup + 7) == kGroup + 7,
              "this group's feature sets are served by another group's kernels");
template void render_rows_kernel<kGroup + 0>(const Renderer&, int, int, Image&, RayCounts&);
template void render_rows_kernel<kGroup + 1>(const Renderer&, int, int, Image&, RayCounts&);
template void render_rows_kernel<kGroup + 2>(const Renderer&, int, int, Image&, RayCounts&);
template void render_rows_kernel<kGroup + 3>(const Renderer&, int, int, Image&, RayCounts&);
template void render_rows_kernel<kGroup + 4>(const Renderer&, int, int, Image&, RayCounts&);
template void render_rows_kernel<kGroup + 5>(const Renderer&, int, int, Image&, RayCounts&);
template void render_rows_kernel<kGroup + 6>(const Renderer&, int, int, Image&, RayCounts&);
template void render_rows_kernel<kGroup + 7>(const Renderer&, int, int, Image&, RayCounts&);

}  // namespace rt2
