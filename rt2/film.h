// rt2/film.h — where samples accumulate: per pixel, the running sum of its samples'
// colours (with Kahan's compensation, so 1,024 samples average to within an ulp) and how
// many samples it holds.
//
// A frame is rendered in passes, each adding a range of every pixel's samples in the order
// of their index; the film keeps the sum and its compensation between passes, so
// `--subpixels 8 --passes 8` adds the same values in the same order as one pass of 8 and
// gives the same bits. Pixels are independent: tiles and threads write disjoint pixels.
#pragma once

#include <cstdint>
#include <vector>

#include "rt2/image.h"
#include "rt2/ray.h"

namespace rt2 {

class Film {
 public:
  Film() = default;
  // A film of width x height pixels holding no sample (check_image_fits first).
  Film(int width, int height);

  // Drops every sample (keeps the memory, for the next frame).
  void clear();

  int width() const { return width_; }
  int height() const { return height_; }
  // Samples pixel (x, y) holds.
  std::uint32_t samples(int x, int y) const { return samples_[index(x, y)]; }

  // Adds one sample's colour (lanes x y z) to pixel (x, y).
  MLIB_INLINE void add(int x, int y, const vec4& color) {
    const std::size_t i = index(x, y);
    // Compensated (Kahan) summation, as the renderer has always averaged its subpixels.
    const vec4 y_ = color - carry_[i];
    const vec4 t = sum_[i] + y_;
    carry_[i] = (t - sum_[i]) - y_;
    sum_[i] = t;
    ++samples_[i];
  }

  // The mean of each pixel's samples, into `image` (resized); a pixel without samples is
  // black. A mean that is NaN or infinite (never expected) is written as black and counted
  // in the return value.
  std::uint64_t resolve(Image& image) const;

 private:
  std::size_t index(int x, int y) const { return std::size_t(y) * std::size_t(width_) + std::size_t(x); }
  int width_ = 0, height_ = 0;
  std::vector<vec4> sum_, carry_;
  std::vector<std::uint32_t> samples_;
};

}  // namespace rt2
