// rt2/film.cpp — a film's storage and its mean (see film.h).
#include "rt2/film.h"

#include <algorithm>
#include <cmath>

namespace rt2 {

Film::Film(int width, int height)
    : width_(width), height_(height), sum_(std::size_t(width) * std::size_t(height)),
      carry_(sum_.size()), samples_(sum_.size(), 0) {}

void Film::clear() {
  std::fill(sum_.begin(), sum_.end(), vec4());
  std::fill(carry_.begin(), carry_.end(), vec4());
  std::fill(samples_.begin(), samples_.end(), 0u);
}

std::uint64_t Film::resolve(Image& image) const {
  if (image.width != width_ || image.height != height_) image = Image(width_, height_);
  std::uint64_t nonfinite = 0;
  for (std::size_t i = 0; i < sum_.size(); ++i) {
    vec4 mean;
    if (samples_[i] > 0) mean = sum_[i] / float(samples_[i]);
    if (!(std::isfinite(mean[0]) && std::isfinite(mean[1]) && std::isfinite(mean[2]))) {
      ++nonfinite;  // never expected: counted so that tests can insist on 0
      mean = vec4();
    }
    for (int c = 0; c < 3; ++c) image.rgb[3 * i + std::size_t(c)] = mean[c];
  }
  return nonfinite;
}

}  // namespace rt2
