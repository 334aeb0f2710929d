// rt2/image/image.h — a rendered frame: linear RGB floats, row-major, top row first.
#pragma once

#include <cstddef>
#include <vector>

namespace rt2 {

// Throws rt2::Error, before anything is allocated, when a width x height frame (its film,
// film.h, and its image) would not fit in the memory available now (MemAvailable in
// /proc/meminfo).
void check_image_fits(int width, int height);
// Bytes of memory available to a new allocation now: MemAvailable in /proc/meminfo, else
// the free physical pages.
double available_memory_bytes();

struct Image {
  int width = 0;
  int height = 0;
  std::vector<float> rgb;  // 3 floats per pixel

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgb(std::size_t(w) * std::size_t(h) * 3, 0.0f) {}
  float* row(int y) { return rgb.data() + std::size_t(y) * std::size_t(width) * 3; }
  const float* pixel(int x, int y) const {
    return rgb.data() + (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3;
  }
};

}  // namespace rt2
