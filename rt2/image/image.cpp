// rt2/image/image.cpp — the memory available, and its check for frame buffers.
#include "rt2/image/image.h"

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "rt2/base/error.h"

namespace rt2 {

double available_memory_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  double kib = 0;
  std::string unit;
  while (meminfo >> key >> kib >> unit)
    if (key == "MemAvailable:") return kib * 1024.0;
  return double(sysconf(_SC_AVPHYS_PAGES)) * double(sysconf(_SC_PAGESIZE));
}

void check_image_fits(int width, int height) {
  // The film (two vec4 and a count per pixel, film.h) and the image (three floats).
  const double need = double(width) * double(height) * (2.0 * 16.0 + 4.0 + 3.0 * sizeof(float));
  const double have = available_memory_bytes();
  if (need > have) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "a %d x %d image needs %.1f GiB of memory (film and image), but only %.1f GiB "
                  "are available",
                  width, height, need / 1073741824.0, have / 1073741824.0);
    throw Error(buf);
  }
}

}  // namespace rt2
