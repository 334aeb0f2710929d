// rt2/render/supersampling.h — where the N subpixels of a pixel are (thesis 3.4).
//
// Offsets are in pixel units, inside [0, 1) x [0, 1) from the pixel's top-left corner; a
// pixel's colour is the plain average of its N samples. N is any integer >= 1.
//  * grid: floor(sqrt(N)) rows; the N samples are spread over the rows as evenly as
//    possible (row i gets floor(N(i+1)/rows) - floor(N i/rows)) and each row is as tall
//    as its share of the samples, so every sample is at the centre of a cell of area 1/N
//    and the samples' mean is the pixel centre. N = 1 is the pixel centre; a perfect
//    square is the usual uniform grid.
//  * circle: the thesis's pattern — N points evenly spaced on a circle around the pixel
//    centre. Its radius sqrt(1/6) ~ 0.408 gives the samples the same mean squared
//    distance from the centre as a uniform distribution over the pixel, and the phase
//    pi/(4N) guarantees that no two samples share an x or a y coordinate (see the .cpp),
//    so a horizontal or vertical edge crossing the pixel is resolved into N + 1 levels
//    rather than the grid's sqrt(N) + 1. N = 1 is the pixel centre.
#pragma once

#include <string>
#include <vector>

namespace rt2 {

enum class Pattern { grid, circle };

struct SubpixelOffset {
  float x, y;
};

// Throws rt2::Error for n < 1.
std::vector<SubpixelOffset> subpixel_offsets(int n, Pattern pattern);

const char* pattern_name(Pattern p);
// "grid" / "circle"; throws rt2::Error naming the value otherwise.
Pattern parse_pattern(const std::string& name);

}  // namespace rt2
