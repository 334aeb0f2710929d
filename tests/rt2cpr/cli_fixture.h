// tests/rt2cpr/cli_fixture.h — running the rt2cpr program from a test: its exit status,
// stdout and stderr, in a fresh folder per test.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/rt2/temp_dir.h"

namespace rt2::test {

namespace fs = std::filesystem;

// The environment rt2cpr runs in. Under AddressSanitizer its leak check is off in these
// child processes: LeakSanitizer's stop-the-world tracer intermittently crashes at the exit
// of a process that has dlopen'ed OpenImageIO (signal 11 while it walks the threads), which
// would make an error path look like a crash. ASan and UBSan stay on; the library's leak
// checks run in rt2_tests itself.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr const char* kChildEnv = "ASAN_OPTIONS=detect_leaks=0 ";
#else
inline constexpr const char* kChildEnv = "";
#endif

struct Outcome {
  int status;
  std::string out, err;
};

class Cli : public ::testing::Test {
 protected:
  std::string path(const std::string& name) const { return dir_.path(name); }
  void write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name), std::ios::binary) << text;
  }
  static std::string slurp(const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
  Outcome run(const std::string& args) const {
    return run_command(std::string(RT2CPR_BIN) + " " + args);
  }
  // A shell command (a program and its arguments) run in the same environment.
  Outcome run_command(const std::string& command) const {
    const std::string cmd = std::string(kChildEnv) + command + " >" + path("stdout") + " 2>" +
                            path("stderr");
    const int raw = std::system(cmd.c_str());
    return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(path("stdout")), slurp(path("stderr"))};
  }
  // Only the given files exist in the test folder (besides the captured streams).
  std::size_t files_other_than_streams() const {
    std::size_t n = 0;
    for (const auto& e : fs::directory_iterator(dir_.root())) {
      const std::string f = e.path().filename().string();
      n += f != "stdout" && f != "stderr";
    }
    return n;
  }
  // A failure: non-zero exit, exactly one line on stderr that mentions `needle`.
  void expect_clean_failure(const Outcome& r, const std::string& needle) const {
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.status, -1) << "crashed";
    ASSERT_FALSE(r.err.empty());
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "not one line: " << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
  }

  TempDir dir_{"rt2cpr"};  // a fresh one per test
};

// A tiny, quiet render.
inline const char* kTiny = "--width 24 --height 16 --quiet";

}  // namespace rt2::test
