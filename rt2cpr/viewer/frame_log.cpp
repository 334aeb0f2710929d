// rt2cpr/viewer/frame_log.cpp — frame intervals and the CSV.
#include "rt2cpr/viewer/frame_log.h"

#include <algorithm>
#include <cstdio>
#include <map>

namespace rt2cpr::viewer {

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

}  // namespace

std::string FrameLog::csv() const {
  std::string s = "time_s,kind,pass,passes,width,height,render_ms,rays\n";
  char line[160];
  for (const FrameRecord& f : frames_) {
    std::snprintf(line, sizeof line, "%.4f,%s,%d,%d,%d,%d,%.3f,%llu\n", f.time_s,
                  f.moving ? "moving" : "still", f.pass, f.passes, f.width, f.height, f.render_ms,
                  static_cast<unsigned long long>(f.rays));
    s += line;
  }
  return s;
}

double FrameLog::moving_fps() const {
  std::vector<double> intervals;
  for (std::size_t i = 1; i < frames_.size(); ++i)
    if (frames_[i].moving && frames_[i - 1].moving)
      intervals.push_back(frames_[i].time_s - frames_[i - 1].time_s);
  const double m = median(intervals);
  return m > 0.0 ? 1.0 / m : 0.0;
}

std::string FrameLog::summary() const {
  std::size_t moving = 0, stills = 0;
  std::map<std::pair<int, int>, std::size_t> sizes;  // moving frames per resolution
  std::vector<double> ms;
  for (const FrameRecord& f : frames_) {
    if (f.moving) {
      ++moving;
      ++sizes[{f.width, f.height}];
      ms.push_back(f.render_ms);
    } else if (f.pass == f.passes) {
      ++stills;
    }
  }
  char b[256];
  std::snprintf(b, sizeof b, "moving: %zu frames, %.1f fps shown (median), %.2f ms to render (median)",
                moving, moving_fps(), median(ms));
  std::string s = b;
  if (!sizes.empty()) {
    s += ", at";
    for (const auto& [size, n] : sizes) {
      std::snprintf(b, sizeof b, " %dx%d (%zu)", size.first, size.second, n);
      s += b;
    }
  }
  std::snprintf(b, sizeof b, "; converged stills: %zu", stills);
  return s + b;
}

}  // namespace rt2cpr::viewer
