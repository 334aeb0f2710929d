// rt2/kernels.cpp — explicit instantiations of the render kernel. The build compiles this
// file eight times with RT2_KERNEL_GROUP = 0..7; group g holds feature sets 8g .. 8g+7,
// so the 64 specialisations compile in parallel.
#include "rt2/tracer.h"

#ifndef RT2_KERNEL_GROUP
#error "compile with -DRT2_KERNEL_GROUP=<0..7>"
#endif

namespace rt2 {

constexpr unsigned kGroup = RT2_KERNEL_GROUP * 8u;
template void render_rows_kernel<kGroup + 0>(const Renderer&, int, int, Image&, RayCounts&);
template void render_rows_kernel<kGroup + 1>(const Renderer&, int, int, Image&, RayCounts&);
template void render_rows_kernel<kGroup + 2>(const Renderer&, int, int, Image&, RayCounts&);
template void render_rows_kernel<kGroup + 3>(const Renderer&, int, int, Image&, RayCounts&);
template void render_rows_kernel<kGroup + 4>(const Renderer&, int, int, Image&, RayCounts&);
template void render_rows_kernel<kGroup + 5>(const Renderer&, int, int, Image&, RayCounts&);
template void render_rows_kernel<kGroup + 6>(const Renderer&, int, int, Image&, RayCounts&);
template void render_rows_kernel<kGroup + 7>(const Renderer&, int, int, Image&, RayCounts&);

}  // namespace rt2
