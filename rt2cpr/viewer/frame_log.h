// rt2cpr/viewer/frame_log.h — the viewer's record of the frames it showed: what
// `--frame-log FILE.csv` writes and the frame rates it prints when the window closes.
//
// The frame rate while moving is the one a user sees: frames shown per second, measured
// between consecutive moving frames (the interval from one to the next, whatever made it:
// rendering, the window, the rest of the machine), as their median.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rt2cpr::viewer {

struct FrameRecord {
  double time_s = 0.0;  // when it was shown, since the window opened
  bool moving = false;
  int pass = 0, passes = 1;  // a still's passes done, of passes
  int width = 0, height = 0;
  double render_ms = 0.0;
  std::uint64_t rays = 0;
};

class FrameLog {
 public:
  void add(const FrameRecord& r) { frames_.push_back(r); }
  // time_s,kind,pass,passes,width,height,render_ms,rays: a header line, then one per frame.
  std::string csv() const;
  // Shown frames per second while moving: 1 / the median interval between consecutive
  // moving frames; 0 with fewer than two.
  double moving_fps() const;
  // "moving: N frames, F fps (median), W x H ...; still: ..." for the end of a session.
  std::string summary() const;

 private:
  std::vector<FrameRecord> frames_;
};

}  // namespace rt2cpr::viewer
