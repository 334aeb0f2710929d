// rt2/render/tile.h — a rectangle of pixels: the unit of work the schedulers hand out
// (schedule.h), a film resolves (film.h) and an MPI job sends between processes.
#pragma once

#include <cstddef>

namespace rt2 {

// Columns [x0, x1), rows [y0, y1).
struct Tile {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  std::size_t pixels() const { return std::size_t(width()) * std::size_t(height()); }
};

}  // namespace rt2
