// rt2/render/renderer.cpp — a renderer's kernel, chosen once.
#include "rt2/render/renderer.h"

#include "rt2/render/kernel_table.h"

namespace rt2 {

Renderer::Renderer(const CompiledScene& scene, const View& view)
    : scene_(scene), view_(view) {
  view_.settings.validate();
  offsets_ = subpixel_offsets(view_.settings.subpixels, view_.settings.pattern);
  kernel_ = render_kernels(scene_.accel.isa).render_tile[view_.settings.watertight ? 1 : 0];
}

}  // namespace rt2
