// tests/rt2/base/layout_test.cpp — the source tree's layout rules, checked on the files: the
// per-ISA kernel (rt2/kernel/) is included by nothing outside it, every kernel file includes
// rt2/kernel/kernel.h, which refuses to compile without RT2_ISA, and README.md's layout list
// names every folder of rt2/.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#ifndef RT2_SOURCE_DIR
#error "the build defines RT2_SOURCE_DIR as the repository root"
#endif

namespace fs = std::filesystem;

namespace {

const fs::path kRoot = RT2_SOURCE_DIR;

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The C++ sources below `dir` (relative to the repository root).
std::vector<fs::path> sources(const std::string& dir) {
  std::vector<fs::path> out;
  for (const auto& e : fs::recursive_directory_iterator(kRoot / dir)) {
    const std::string ext = e.path().extension().string();
    if (e.is_regular_file() && (ext == ".h" || ext == ".cpp")) out.push_back(e.path());
  }
  return out;
}

bool in_kernel(const fs::path& p) {
  return fs::relative(p, kRoot).string().rfind("rt2/kernel/", 0) == 0;
}

TEST(Layout, NoFileOutsideTheKernelFolderIncludesAKernelHeader) {
  std::size_t checked = 0;
  for (const char* dir : {"mlib", "rt2", "rt2cpr", "tests"})
    for (const fs::path& p : sources(dir)) {
      if (in_kernel(p)) continue;
      ++checked;
      EXPECT_EQ(read(p).find("#include \"rt2/kernel/"), std::string::npos)
          << fs::relative(p, kRoot) << " includes a kernel header: rt2/kernel/ is compiled per "
          << "instruction set and reached through rt2/render/kernel_table.h or trace.h";
    }
  EXPECT_GT(checked, 200u);
}

TEST(Layout, EveryKernelFileIncludesTheKernelHeader) {
  std::size_t checked = 0;
  for (const fs::path& p : sources("rt2/kernel")) {
    if (p.filename() == "kernel.h") continue;
    ++checked;
    EXPECT_NE(read(p).find("#include \"rt2/kernel/kernel.h\""), std::string::npos)
        << fs::relative(p, kRoot) << " does not include rt2/kernel/kernel.h";
  }
  EXPECT_GT(checked, 10u);
}

// The compiler itself: kernel.h (and so every kernel file) stops a build without RT2_ISA.
TEST(Layout, TheKernelHeaderRefusesToCompileWithoutAnInstructionSet) {
  const char* cxx = std::getenv("CXX");
  const std::string compile = std::string(cxx && *cxx ? cxx : "g++") + " -std=c++20 -fsyntax-only -I" +
                              kRoot.string() + " -x c++ " + (kRoot / "rt2/kernel/kernel.h").string();
  const auto run = [](const std::string& cmd, std::string& output) {
    std::unique_ptr<FILE, int (*)(FILE*)> pipe(::popen((cmd + " 2>&1").c_str(), "r"), ::pclose);
    char buf[4096];
    while (pipe && std::fgets(buf, sizeof buf, pipe.get())) output += buf;
    return pipe ? ::pclose(pipe.release()) : -1;
  };
  std::string without, with;
  EXPECT_NE(run(compile, without), 0) << without;
  EXPECT_NE(without.find("compiled once per instruction set"), std::string::npos) << without;
  EXPECT_EQ(run(compile + " -DRT2_ISA=sse41", with), 0) << with;
}

TEST(Layout, TheReadmeLayoutNamesEveryFolderOfRt2) {
  const std::string readme = read(kRoot / "README.md");
  std::size_t folders = 0;
  for (const auto& e : fs::directory_iterator(kRoot / "rt2")) {
    if (!e.is_directory()) continue;
    ++folders;
    const std::string name = "rt2/" + e.path().filename().string() + "/";
    EXPECT_NE(readme.find(name), std::string::npos) << "README.md's layout does not name " << name;
  }
  EXPECT_GE(folders, 10u);
}

}  // namespace
