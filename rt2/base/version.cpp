// rt2/base/version.cpp — build identity (see version.h). The build defines RT2_GIT_COMMIT for
// this file only, so that a new commit recompiles nothing else.
#include "rt2/base/version.h"

#include <fstream>

#include "rt2/base/isa.h"

#ifndef RT2_GIT_COMMIT
#define RT2_GIT_COMMIT "unknown"
#endif

namespace rt2 {

const char* git_commit() { return RT2_GIT_COMMIT; }

const char* compiler() {
#if defined(__clang__)
  return "clang++ " __clang_version__;
#elif defined(__GNUC__)
  return "g++ " __VERSION__;
#else
  return "unknown compiler";
#endif
}

const char* build_isa() {
#if defined(MLIB_SCALAR)
  return "scalar";
#elif defined(__AVX512F__)
  return "avx512";
#elif defined(__AVX2__)
  return "avx2";
#elif defined(__SSE4_1__)
  return "sse4.1";
#else
  return "sse2";
#endif
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos)
      return line.substr(line.find(':') + 2);
  return "unknown";
}

std::string version_line() {
  std::string kernels;
  for (Isa isa : built_isas()) kernels += std::string(kernels.empty() ? "" : " ") + isa_name(isa);
  return std::string("rt2 ") + kVersion + " (commit " + git_commit() + ", " + compiler() +
         ", baseline " + build_isa() + ", ray kernels " + kernels + ", this CPU runs " +
         isa_name(best_isa()) + ")";
}

}  // namespace rt2
