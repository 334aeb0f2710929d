// rt2/kernel/generate.h — the render kernel's first stage: the primary rays of a block's
// samples, in packets of one sample over 4 x 4 pixels, each ray the bits Camera::ray gives.
#pragma once

#include <algorithm>
#include <bit>
#include <cfloat>
#include <cstdint>

#include "rt2/kernel/kernel.h"

#include "mlib/vfloat.h"
#include "rt2/kernel/batches.h"
#include "rt2/render/renderer.h"

namespace rt2::RT2_ISA {

// The 16 rays of a whole 4 x 4 packet (image x per column, y per row; samples sample0 +
// row * row_step + column * column_step), appended in one SIMD pass: lane by lane what
// Camera::ray_at computes, the same bits (normalize's dot product in dpps's order, and its
// rescaling path, through ray_at itself, for the lanes that need it).
inline void push_packet(const Camera& cam, const float (&image_x)[4], const float (&image_y)[4],
                        std::uint32_t sample0, std::uint32_t row_step, std::uint32_t column_step,
                        PathRays& rays) {
  using V = mlib::vfloat<mlib::kWidestLanes>;
  constexpr int kLanes = V::size;
  auto& c = rays.columns();
  c.reserve(c.size() + 16);
  const std::size_t at = c.size();
  alignas(64) float xs[16], ys[16];
  for (int l = 0; l < 16; ++l) {
    xs[l] = image_x[l % 4];
    ys[l] = image_y[l / 4];
    c.u(PathRays::kSample)[at + std::size_t(l)] =
        sample0 + std::uint32_t(l / 4) * row_step + std::uint32_t(l % 4) * column_step;
  }
  const vec4 &forward = cam.forward(), &right = cam.right(), &up = cam.up(), &eye = cam.position();
  for (int g = 0; g < 16; g += kLanes) {
    const V x = V::load(xs + g), y = V::load(ys + g);
    V d[4];
    for (int a = 0; a < 4; ++a)
      d[a] = (V::broadcast(forward[a]) + V::broadcast(right[a]) * x) + V::broadcast(up[a]) * y;
    const V len2 = (d[0] * d[0] + d[1] * d[1]) + (d[2] * d[2] + d[3] * d[3]);
    const V len = sqrt(len2);
    for (int a = 0; a < 4; ++a) {
      (d[a] / len).storeu(c.f(PathRays::kDir + a) + at + std::size_t(g));
      V::broadcast(eye[a]).storeu(c.f(PathRays::kOrg + a) + at + std::size_t(g));
    }
    for (int k = 0; k < 3; ++k) V::broadcast(1.0f).storeu(c.f(PathRays::kWeight + k) + at + std::size_t(g));
    const unsigned normal = mlib::bits((len2 >= V::broadcast(FLT_MIN)) & (len2 <= V::broadcast(FLT_MAX)));
    for (unsigned m = ~normal & ((1u << kLanes) - 1); m; m &= m - 1) {
      const int l = g + std::countr_zero(m);
      const vec4 dir = cam.ray_at(xs[l], ys[l]).dir;
      for (int a = 0; a < 4; ++a) c.f(PathRays::kDir + a)[at + std::size_t(l)] = dir[a];
    }
  }
  c.extend(16);
}

// The primary rays of samples [s0, s1) of the block's pixels, packet by packet:
// 4 x 4 pixels (fewer at the block's right and bottom edges) for one sample. A sample's
// colour is b.colors[((y - y0) bw + x - x0) (s1 - s0) + k - s0] whatever the ray order.
inline void generate(const Renderer& r, const Tile& block, int s0, int s1, Batches& b) {
  const RenderSettings& st = r.settings();
  const Camera& cam = r.camera();
  const auto& offsets = r.offsets();
  const int samples = s1 - s0, bw = block.x1 - block.x0;
  b.rays.clear();
  // clear + push_back, not assign(1, 0): GCC outlines vector<uint32_t>'s fill in the AVX-512
  // unit only, a std:: function with wide instructions that isa_test rightly flags
  b.packet_begin.clear();
  b.packet_begin.push_back(0);
  for (int gy = block.y0; gy < block.y1; gy += 4)
    for (int gx = block.x0; gx < block.x1; gx += 4)
      for (int k = s0; k < s1; ++k) {
        const SubpixelOffset& o = offsets[k];
        const int nx = std::min(gx + 4, block.x1) - gx, ny = std::min(gy + 4, block.y1) - gy;
        float image_x[4], image_y[4];  // per column and row of the packet (Camera::ray)
        for (int j = 0; j < nx; ++j) image_x[j] = cam.image_x(float(gx + j) + o.x, st.width, st.height);
        for (int j = 0; j < ny; ++j) image_y[j] = cam.image_y(float(gy + j) + o.y, st.height);
        if (nx == 4 && ny == 4) {
          push_packet(cam, image_x, image_y,
                      static_cast<std::uint32_t>(((gy - block.y0) * bw + gx - block.x0) * samples + k - s0),
                      static_cast<std::uint32_t>(bw * samples), static_cast<std::uint32_t>(samples),
                      b.rays);
          b.packet_begin.push_back(static_cast<std::uint32_t>(b.rays.size()));
          continue;
        }
        for (int y = gy; y < gy + ny; ++y) {
          vec4 dir[4];
          std::uint32_t sample[4];
          for (int j = 0; j < 4; ++j) {
            const int x = gx + std::min(j, nx - 1);  // a short row repeats its last ray
            dir[j] = cam.ray_at(image_x[x - gx], image_y[y - gy]).dir;
            sample[j] = static_cast<std::uint32_t>(((y - block.y0) * bw + x - block.x0) * samples +
                                                   k - s0);
          }
          b.rays.push_row(cam.position(), dir, sample, nx);
        }
        b.packet_begin.push_back(static_cast<std::uint32_t>(b.rays.size()));
      }
}

}  // namespace rt2::RT2_ISA
