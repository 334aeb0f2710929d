// rt2/image/image_compare.cpp — SSIM, and the combined comparison.
#include "rt2/image/image_compare.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "rt2/base/error.h"

namespace rt2 {

namespace {

std::vector<float> luminance(const Image& img) {
  std::vector<float> y(std::size_t(img.width) * img.height);
  for (std::size_t i = 0; i < y.size(); ++i) {
    const float* p = img.rgb.data() + 3 * i;
    const auto c = [](float v) { return std::clamp(v, 0.0f, 1.0f); };
    y[i] = 0.2126f * c(p[0]) + 0.7152f * c(p[1]) + 0.0722f * c(p[2]);
  }
  return y;
}

// Separable Gaussian blur (sigma 1.5, radius 5), edges clamped.
std::vector<double> blur(const std::vector<double>& in, int w, int h) {
  constexpr int kR = 5;
  double k[2 * kR + 1], sum = 0;
  for (int i = -kR; i <= kR; ++i) sum += k[i + kR] = std::exp(-(i * i) / (2 * 1.5 * 1.5));
  for (double& v : k) v /= sum;
  std::vector<double> tmp(in.size()), out(in.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double s = 0;
      for (int i = -kR; i <= kR; ++i) s += k[i + kR] * in[std::size_t(y) * w + std::clamp(x + i, 0, w - 1)];
      tmp[std::size_t(y) * w + x] = s;
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double s = 0;
      for (int i = -kR; i <= kR; ++i) s += k[i + kR] * tmp[std::size_t(std::clamp(y + i, 0, h - 1)) * w + x];
      out[std::size_t(y) * w + x] = s;
    }
  return out;
}

}  // namespace

double ssim(const Image& a, const Image& b) {
  const int w = a.width, h = a.height;
  const std::vector<float> ya = luminance(a), yb = luminance(b);
  const std::size_t n = ya.size();
  std::vector<double> xa(n), xb(n), aa(n), bb(n), ab(n);
  for (std::size_t i = 0; i < n; ++i) {
    xa[i] = ya[i];
    xb[i] = yb[i];
    aa[i] = double(ya[i]) * ya[i];
    bb[i] = double(yb[i]) * yb[i];
    ab[i] = double(ya[i]) * yb[i];
  }
  const auto ma = blur(xa, w, h), mb = blur(xb, w, h), saa = blur(aa, w, h),
             sbb = blur(bb, w, h), sab = blur(ab, w, h);
  constexpr double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
  double total = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double va = saa[i] - ma[i] * ma[i], vb = sbb[i] - mb[i] * mb[i];
    const double cov = sab[i] - ma[i] * mb[i];
    total += ((2 * ma[i] * mb[i] + c1) * (2 * cov + c2)) /
             ((ma[i] * ma[i] + mb[i] * mb[i] + c1) * (va + vb + c2));
  }
  return total / double(n);
}

double edge_rmse(const Image& image, const Image& reference, std::size_t& pixels) {
  const int w = reference.width, h = reference.height;
  const std::vector<float> y = luminance(reference);
  double sum = 0;
  pixels = 0;
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      float lo = 1.0f, hi = 0.0f;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const float v = y[std::size_t(std::clamp(py + dy, 0, h - 1)) * w + std::clamp(px + dx, 0, w - 1)];
          lo = std::min(lo, v);
          hi = std::max(hi, v);
        }
      if (hi - lo <= 0.1f) continue;
      ++pixels;
      const float* a = image.pixel(px, py);
      const float* b = reference.pixel(px, py);
      for (int c = 0; c < 3; ++c) sum += double(a[c] - b[c]) * double(a[c] - b[c]);
    }
  return pixels ? std::sqrt(sum / (3.0 * double(pixels))) : 0.0;
}

ImageError compare_images(const Image& image, const Image& reference) {
  if (image.width != reference.width || image.height != reference.height)
    throw Error("reference image is " + std::to_string(reference.width) + "x" +
                std::to_string(reference.height) + ", the render is " +
                std::to_string(image.width) + "x" + std::to_string(image.height));
  ImageError e;
  double sum = 0.0;
  for (std::size_t i = 0; i < image.rgb.size(); ++i) {
    const double d = double(image.rgb[i]) - double(reference.rgb[i]);
    sum += d * d;
  }
  e.rmse = image.rgb.empty() ? 0.0 : std::sqrt(sum / double(image.rgb.size()));
  e.psnr = e.rmse > 0.0 ? 20.0 * std::log10(1.0 / e.rmse) : std::numeric_limits<double>::infinity();
  e.ssim = ssim(image, reference);
  e.edge_rmse = edge_rmse(image, reference, e.edge_pixels);
  return e;
}

}  // namespace rt2
