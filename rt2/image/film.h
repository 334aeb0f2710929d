// rt2/image/film.h — where samples accumulate: per pixel, the running sum of its samples'
// colours (with Kahan's compensation, so 1,024 samples average to within an ulp) and how
// many samples it holds.
//
// A frame is rendered in passes, each adding a range of every pixel's samples in the order
// of their index; the film keeps the sum and its compensation between passes, so
// `--subpixels 8 --passes 8` adds the same values in the same order as one pass of 8 and
// gives the same bits. Pixels are independent: tiles and threads write disjoint pixels.
//
// Invariant: a pixel's sum and compensation are 0 while it holds no sample, whatever its
// memory holds, and its compensation is sum - sum while it holds one (what Kahan's first
// step leaves, NaN included): clearing resets the counts only, and a frame's first sample
// per pixel neither reads the film's sums nor writes a compensation.
#pragma once

#include <cstdint>
#include <vector>

#include "rt2/image/image.h"
#include "rt2/geometry/ray.h"
#include "rt2/render/tile.h"

namespace rt2 {

class Film {
 public:
  Film() = default;
  // A film of width x height pixels holding no sample (check_image_fits first).
  Film(int width, int height);

  // Drops every sample (keeps the memory, for the next frame): the counts to 0.
  void clear();
  // Drops the samples of the pixels of `tile` only.
  void clear(const Tile& tile);

  int width() const { return width_; }
  int height() const { return height_; }
  // Samples pixel (x, y) holds.
  std::uint32_t samples(int x, int y) const { return samples_[index(x, y)]; }

  // Adds one sample's colour (lanes x y z) to pixel (x, y).
  MLIB_INLINE void add(int x, int y, const vec4& color) { add(x, y, &color, 1); }
  // Adds `count` samples' colours to pixel (x, y), in their order: the same as `count`
  // calls of add, with the pixel's state read and written once. Nothing for count <= 0.
  MLIB_INLINE void add(int x, int y, const vec4* colors, int count) {
    if (count <= 0) return;
    const std::size_t i = index(x, y);
    // Compensated (Kahan) summation.
    const std::uint32_t n = samples_[i];
    vec4 sum, carry;
    int k = 0;
    if (n == 0) {
      sum = vec4() + (colors[0] - vec4());  // from zeros; leaves sum - sum to carry
      carry = sum - sum;
      k = 1;
    } else {
      sum = sum_[i];
      carry = n == 1 ? vec4(sum - sum) : carry_[i];
    }
    for (; k < count; ++k) {
      const vec4 y_ = colors[k] - carry;
      const vec4 t = sum + y_;
      carry = (t - sum) - y_;
      sum = t;
    }
    sum_[i] = sum;
    if (n + std::uint32_t(count) > 1) carry_[i] = carry;
    samples_[i] = n + std::uint32_t(count);
  }

  // Asks for the state of the pixels in columns [x0, x1) of rows [y0, y1) to be brought
  // into the caches, ahead of adding to them (a hint: the film of a frame is larger than
  // the caches, and a block's rays take long enough to hide the fetch): the counts and
  // sums, and the compensations where the block's first pixel will hold more than one
  // sample once `adding` more are added.
  void prefetch(int x0, int y0, int x1, int y1, int adding) const {
    const int lines = ((x1 - x0) * int(sizeof(vec4)) + 63) / 64 + 1;
    const bool carried = samples_[index(x0, y0)] + std::uint32_t(adding) > 1;
    for (int y = y0; y < y1; ++y) {
      mlib::prefetch_for_write(&sum_[index(x0, y)], lines);
      if (carried) mlib::prefetch_for_write(&carry_[index(x0, y)], lines);
      mlib::prefetch_for_write(&samples_[index(x0, y)], 2);
    }
  }

  // The mean of each pixel's samples, into `image` (resized); a pixel without samples is
  // black. A mean that is NaN or infinite (never expected) is written as black and counted
  // in the return value.
  std::uint64_t resolve(Image& image) const;
  // The same means for the pixels of `tile` alone, into `rgb`: 3 floats per pixel, row by
  // row (tile.pixels() x 3 floats); the same bits as resolve(Image&) gives them.
  std::uint64_t resolve(const Tile& tile, float* rgb) const;

 private:
  // Pixel i's mean into rgb[0..2]; false (and black) when it is NaN or infinite.
  bool mean(std::size_t i, float* rgb) const;
  std::size_t index(int x, int y) const { return std::size_t(y) * std::size_t(width_) + std::size_t(x); }
  int width_ = 0, height_ = 0;
  std::vector<vec4> sum_, carry_;
  std::vector<std::uint32_t> samples_;
};

}  // namespace rt2
