// rt2/image/image_compare.h — how far an image is from a reference.
//
// RMSE over the RGB channels (in double), and PSNR = 20 log10(1 / RMSE) with peak 1.0
// (OIIO's own PSNR would take the images' maximum as the peak, which changes with
// highlights); SSIM (Wang et al. 2004: 11x11 Gaussian window, sigma 1.5,
// K1 = 0.01, K2 = 0.03, dynamic range 1) is computed here on luminance, with both images
// clamped to [0, 1] first, and averaged over the image. Identical images give RMSE 0,
// PSNR +inf and SSIM 1. The edge error is defined at edge_rmse below.
#pragma once

#include <cstddef>

#include "rt2/image/image.h"

namespace rt2 {

struct ImageError {
  double rmse = 0.0;
  double psnr = 0.0;  // dB, peak value 1; +inf for identical images
  double ssim = 1.0;
  double edge_rmse = 0.0;         // RMSE over the reference's edge pixels (0 if none)
  std::size_t edge_pixels = 0;    // how many there are
};

// Throws rt2::Error when the sizes differ.
ImageError compare_images(const Image& image, const Image& reference);

double ssim(const Image& a, const Image& b);

// Edge error, for judging anti-aliasing: the RMSE of `image` against `reference` over the
// reference's edge pixels only, where a pixel is an edge pixel when the reference's
// luminance varies by more than 0.1 within its 3x3 neighbourhood (flat regions, where every
// supersampling pattern agrees, would otherwise dilute the difference between patterns);
// `pixels` receives their count.
double edge_rmse(const Image& image, const Image& reference, std::size_t& pixels);

}  // namespace rt2
