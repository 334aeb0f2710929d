// rt2cpr/frame_files.h — `--output out_####.png`: one image file per frame, the run of '#'
// in the file name replaced by the frame's number (1, 2, ... as rt2cpr prints them),
// zero-padded to the run's length.
#pragma once

#include <functional>
#include <string>

#include "rt2/image/image.h"

namespace rt2cpr {

// What is done with each frame's image, and its index (0, 1, ...), once it is rendered.
using FrameSink = std::function<void(int frame, const rt2::Image& image)>;

// Whether the file name of `path` (not its folders) holds a '#'.
bool names_frames(const std::string& path);

// `path` with the first run of '#' in its file name replaced by `frame`, zero-padded to the
// run's length (longer numbers are written whole).
std::string frame_file(const std::string& path, int frame);

}  // namespace rt2cpr
