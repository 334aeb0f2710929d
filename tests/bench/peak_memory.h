// tests/bench/peak_memory.h — how much resident memory a piece of work takes at its peak,
// from Linux's /proc/self: freed heap memory is returned to the system first (malloc_trim),
// the peak is reset (writing 5 to /proc/self/clear_refs, Linux 4.0 on), and the peak after
// the work (VmHWM) less the resident set before it (VmRSS) is the work's. 0 where /proc
// cannot tell.
#pragma once

#include <malloc.h>

#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace bench {

// The "Vm...:" line `key` of /proc/self/status, in bytes; 0 if absent.
inline std::size_t proc_status_bytes(const char* key) {
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return 0;
  char line[256];
  std::size_t kb = 0;
  const std::size_t n = std::strlen(key);
  while (std::fgets(line, sizeof line, f))
    if (std::strncmp(line, key, n) == 0 && line[n] == ':') {
      kb = std::size_t(std::strtoull(line + n + 1, nullptr, 10));
      break;
    }
  std::fclose(f);
  return kb * 1024;
}

// Started at construction; bytes() is the peak growth of the resident set since then.
class PeakMemory {
 public:
  PeakMemory() {
    malloc_trim(0);
    if (std::FILE* f = std::fopen("/proc/self/clear_refs", "w")) {
      reset_ = std::fputs("5", f) >= 0;
      reset_ = std::fclose(f) == 0 && reset_;
    }
    before_ = proc_status_bytes("VmRSS");
  }
  std::size_t bytes() const {
    if (!reset_) return 0;
    const std::size_t peak = proc_status_bytes("VmHWM");
    return peak > before_ ? peak - before_ : 0;
  }

 private:
  std::size_t before_ = 0;
  bool reset_ = false;
};

}  // namespace bench
