// rt2/image/film.cpp — a film's storage and its mean (see film.h).
#include "rt2/image/film.h"

#include <algorithm>
#include <cmath>

namespace rt2 {

Film::Film(int width, int height)
    : width_(width), height_(height), sum_(std::size_t(width) * std::size_t(height)),
      carry_(sum_.size()), samples_(sum_.size(), 0) {}

void Film::clear() { std::fill(samples_.begin(), samples_.end(), 0u); }

void Film::clear(const Tile& tile) {
  for (int y = tile.y0; y < tile.y1; ++y) {
    const auto row = std::ptrdiff_t(index(tile.x0, y)), end = row + tile.width();
    std::fill(samples_.begin() + row, samples_.begin() + end, 0u);
  }
}

bool Film::mean(std::size_t i, float* rgb) const {
  vec4 m;
  if (samples_[i] > 0) m = sum_[i] / float(samples_[i]);
  // Never expected: counted so that tests can insist on 0.
  const bool finite = std::isfinite(m[0]) && std::isfinite(m[1]) && std::isfinite(m[2]);
  if (!finite) m = vec4();
  for (int c = 0; c < 3; ++c) rgb[c] = m[c];
  return finite;
}

std::uint64_t Film::resolve(Image& image) const {
  if (image.width != width_ || image.height != height_) image = Image(width_, height_);
  return resolve(Tile{0, 0, width_, height_}, image.rgb.data());
}

std::uint64_t Film::resolve(const Tile& tile, float* rgb) const {
  std::uint64_t nonfinite = 0;
  for (int y = tile.y0; y < tile.y1; ++y)
    for (int x = tile.x0; x < tile.x1; ++x, rgb += 3) nonfinite += !mean(index(x, y), rgb);
  return nonfinite;
}

}  // namespace rt2
