// rt2cpr/progress.h — a progress bar on stderr for long renders.
//
// Shown only when stderr is a terminal and only once a frame has taken more than a second;
// erased when the frame ends. No library: a carriage return and a line of text.
#pragma once

#include <chrono>

namespace rt2cpr {

class ProgressBar {
 public:
  explicit ProgressBar(bool enabled);
  void start_frame(int frame, int frames);
  // Portions done out of total (called from worker threads, one at a time).
  void update(int done, int total);
  void end_frame();

 private:
  bool enabled_;
  bool shown_ = false;
  int frame_ = 0, frames_ = 1;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace rt2cpr
