// rt2cpr/progress.cpp — the stderr progress bar.
#include "rt2cpr/progress.h"

#include <unistd.h>

#include <cstdio>

namespace rt2cpr {

ProgressBar::ProgressBar(bool enabled) : enabled_(enabled && ::isatty(STDERR_FILENO)) {}

void ProgressBar::start_frame(int frame, int frames) {
  frame_ = frame;
  frames_ = frames;
  start_ = std::chrono::steady_clock::now();
}

void ProgressBar::update(int done, int total) {
  if (!enabled_) return;
  if (!shown_ && std::chrono::steady_clock::now() - start_ < std::chrono::seconds(1)) return;
  shown_ = true;
  constexpr int kWidth = 40;
  const int filled = total > 0 ? done * kWidth / total : kWidth;
  char bar[kWidth + 1];
  for (int i = 0; i < kWidth; ++i) bar[i] = i < filled ? '#' : '.';
  bar[kWidth] = '\0';
  std::fprintf(stderr, "\r  frame %d/%d [%s] %3d%%", frame_ + 1, frames_, bar,
               total > 0 ? done * 100 / total : 100);
  std::fflush(stderr);
}

void ProgressBar::end_frame() {
  if (!shown_) return;
  std::fprintf(stderr, "\r%*s\r", 70, "");
  std::fflush(stderr);
  shown_ = false;
}

}  // namespace rt2cpr
