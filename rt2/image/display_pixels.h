// rt2/image/display_pixels.h — a rendered image as a screen shows it: 8-bit sRGB with alpha.
//
// The same mapping as a display file format gets (tonemap.h, then the sRGB curve of
// srgb.h): exposure, tone curve, sRGB encoding, rounding to 8 bits. The curve is read from
// a table of 4096 steps over [0, 1], so a value may land one 8-bit step away from what the
// exact curve gives (near black, where the curve is steepest): for a live view, not for
// files, which are written by image_io.h.
#pragma once

#include <cstdint>
#include <vector>

#include "rt2/image/image.h"
#include "rt2/image/tonemap.h"

namespace rt2 {

// `image` into `rgba` (resized): 4 bytes per pixel, R, G, B, A = 255, rows top first.
void to_display_pixels(const Image& image, const Display& display, std::vector<std::uint8_t>& rgba);

}  // namespace rt2
