// rt2cpr/frame_files.cpp — per-frame output file names (see frame_files.h).
#include "rt2cpr/frame_files.h"

#include <string>

namespace rt2cpr {
namespace {

std::size_t name_start(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? 0 : slash + 1;
}

}  // namespace

bool names_frames(const std::string& path) {
  return path.find('#', name_start(path)) != std::string::npos;
}

std::string frame_file(const std::string& path, int frame) {
  const std::size_t first = path.find('#', name_start(path));
  if (first == std::string::npos) return path;
  std::size_t last = first;
  while (last < path.size() && path[last] == '#') ++last;
  std::string number = std::to_string(frame);
  if (number.size() < last - first) number.insert(0, last - first - number.size(), '0');
  return path.substr(0, first) + number + path.substr(last);
}

}  // namespace rt2cpr
