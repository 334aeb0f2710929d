// rt2/base/version.h — what this build of rt2 is: version, commit, compiler and instruction set,
// for `rt2cpr --version` and the statistics file.
#pragma once

#include <string>

namespace rt2 {

inline constexpr const char* kVersion = "0.2.0";

// The git commit the library was built from ("unknown" outside a checkout; a trailing "+"
// when the checkout had uncommitted changes).
const char* git_commit();

// "g++ 12.2.0".
const char* compiler();

// The instruction set the portable code was compiled for ("sse4.1", "avx2", "avx512",
// "scalar"); the ray kernels come in several (rt2/base/isa.h).
const char* build_isa();

// The CPU's model name (/proc/cpuinfo), or "unknown".
std::string cpu_model();

// "rt2 0.2.0 (commit 1234abcd, g++ 12.2.0, baseline sse4.1, ray kernels sse41 avx2 avx512,
// this CPU runs avx512)".
std::string version_line();

}  // namespace rt2
