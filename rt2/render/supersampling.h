// rt2/render/supersampling.h — where the N subpixels of a pixel are (thesis 3.4): offsets in
// pixel units inside [0, 1) x [0, 1) from the pixel's top-left corner; a pixel's colour is
// the plain average of its N samples, N any integer >= 1, N = 1 the pixel centre.
//  * grid: floor(sqrt(N)) rows, the samples spread over them as evenly as possible, each
//    sample at the centre of a cell of area 1/N (a perfect square: the uniform grid);
//  * circle: the thesis's pattern, N points evenly spaced on a circle of radius sqrt(1/6)
//    (the mean squared distance of a uniform pixel) with phase pi/(4N), so no two samples
//    share an x or a y and an axis-aligned edge resolves into N + 1 levels (see the .cpp).
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
