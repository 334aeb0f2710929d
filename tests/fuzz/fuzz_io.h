// tests/fuzz/fuzz_io.h — what the libFuzzer targets (fuzz_scene, fuzz_obj, fuzz_gltf) share:
// a per-process scratch folder in /dev/shm, byte-exact file writes into it, and the one call
// into the loader whose contract is being fuzzed.
//
// The targets go through the real loading path, rt2::load_scene on a file, not an in-memory
// shortcut, so that reading, screening, MTL lookup and path handling are exercised too. The
// folder is in /dev/shm (memory) to keep each execution cheap, and is named after the process
// id so that parallel jobs (-jobs=N) never share files. rt2::Error is the loader's documented
// way to fail and is swallowed; anything else (another exception, a crash, a sanitizer report,
// a hang, a leak) escapes to libFuzzer, which reports it.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <string_view>

#include "rt2/base/error.h"
#include "rt2/io/scene_io.h"

namespace rt2::fuzz {

namespace fs = std::filesystem;

// /dev/shm/rt2-fuzz-<target>-<pid>, created on first use and removed at exit.
inline const fs::path& scratch(const char* target) {
  static const fs::path dir = [&] {
    fs::path d = fs::path("/dev/shm") / ("rt2-fuzz-" + std::string(target) + "-" +
                                         std::to_string(::getpid()));
    fs::create_directories(d);
    std::atexit([] {
      std::error_code ec;
      fs::remove_all(scratch(""), ec);
    });
    return d;
  }();
  return dir;
}

// Writes `bytes` exactly to `path`, replacing it.
inline void write_file(const fs::path& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// Loader warnings (a missing MTL library, ...) would fill the log at thousands of runs a
// second; they go nowhere. Sanitizer and libFuzzer reports do not use std::cerr.
inline void silence_warnings() { std::cerr.rdbuf(nullptr); }

// Loads `path`; a one-line rt2::Error is the expected failure, anything else escapes.
inline void load(const fs::path& path) {
  try {
    (void)rt2::load_scene(path.string());
  } catch (const rt2::Error& e) {
    if (std::string_view(e.what()).find_first_of("\r\n") != std::string_view::npos) {
      std::cout << "rt2::Error message is not one line: " << e.what() << "\n";
      std::abort();
    }
  }
}

}  // namespace rt2::fuzz
