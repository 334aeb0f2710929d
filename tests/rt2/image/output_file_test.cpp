// Output files appear complete or not at all: every write, the flush and the close are
// checked; a full disk, /dev/full, a signal or exit() leave no temporary file; links are
// written through; read-only files and directories are refused.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "rt2/base/error.h"
#include "rt2/image/output_file.h"
#include "tests/rt2/error_of.h"
#include "tests/rt2/small_file_system.h"
#include "tests/rt2/temp_dir.h"

namespace rt2::io {
namespace {

namespace fs = std::filesystem;

std::string slurp(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::size_t entries(const fs::path& dir) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
  return n;
}

using test::error_of;

TEST(OutputFile, WritesTheBytesAndLeavesOnlyTheTarget) {
  const test::TempDir tmp("out_ok");
  write_output_file(tmp.path("a.json"), "{}\n");
  write_output_file(tmp.path("a.json"), "{\"x\": 1}\n");  // replaces
  EXPECT_EQ(slurp(tmp.path("a.json")), "{\"x\": 1}\n");
  EXPECT_EQ(entries(tmp.root()), 1u);
}

TEST(OutputFile, AFullFileSystemFailsWithOneLineAndLeavesNothing) {
  const test::SmallFileSystem disk;
  if (!disk.available()) GTEST_SKIP() << disk.why_not();
  const std::string big(200 * 1024, 'x');
  const std::string msg = error_of([&] { write_output_file(disk.path("big.json"), big); });
  EXPECT_EQ(msg, "cannot write " + disk.path("big.json") + ": No space left on device");
  EXPECT_EQ(disk.entries(), 0u);
  // An existing file on the full disk is left exactly as it was.
  write_output_file(disk.path("small.json"), "old");
  EXPECT_FALSE(error_of([&] { write_output_file(disk.path("small.json"), big); }).empty());
  EXPECT_EQ(slurp(disk.path("small.json")), "old");
  EXPECT_EQ(disk.entries(), 1u);
}

TEST(OutputFile, DevFullFailsEveryWrite) {
  EXPECT_EQ(error_of([] { write_output_file("/dev/full", "x"); }),
            "cannot write /dev/full: No space left on device");
  const test::TempDir tmp("out_devfull");
  fs::create_symlink("/dev/full", tmp.path("s.json"));
  EXPECT_EQ(error_of([&] { write_output_file(tmp.path("s.json"), "{}"); }),
            "cannot write " + tmp.path("s.json") + ": No space left on device");
  EXPECT_TRUE(fs::is_symlink(tmp.path("s.json")));
}

TEST(OutputFile, DevicesAndPipesAreWrittenInPlace) {
  write_output_file("/dev/null", "discarded");
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

TEST(OutputFile, ASymlinkIsWrittenThroughAndStaysALink) {
  const test::TempDir tmp("out_link");
  write_output_file(tmp.path("real.json"), "old");
  fs::create_symlink("real.json", tmp.path("link.json"));
  write_output_file(tmp.path("link.json"), "new");
  EXPECT_TRUE(fs::is_symlink(tmp.path("link.json")));
  EXPECT_EQ(slurp(tmp.path("real.json")), "new");
  // A dangling link creates its target.
  fs::create_symlink("sub/made.json", tmp.path("dangling.json"));
  fs::create_directory(tmp.path("sub"));
  write_output_file(tmp.path("dangling.json"), "made");
  EXPECT_TRUE(fs::is_symlink(tmp.path("dangling.json")));
  EXPECT_EQ(slurp(tmp.path("sub/made.json")), "made");
}

TEST(OutputFile, AReadOnlyFileIsRefusedForEveryone) {
  const test::TempDir tmp("out_ro");
  write_output_file(tmp.path("keep.json"), "mine");
  ::chmod(tmp.path("keep.json").c_str(), 0444);
  EXPECT_NE(error_of([&] { check_output_path(tmp.path("keep.json")); }).find("is read-only"),
            std::string::npos);
  EXPECT_FALSE(error_of([&] { write_output_file(tmp.path("keep.json"), "yours"); }).empty());
  EXPECT_EQ(slurp(tmp.path("keep.json")), "mine");
  EXPECT_EQ(entries(tmp.root()), 1u);
}

TEST(OutputFile, EmptyPathsDirectoriesAndMissingFoldersAreRefusedUpFront) {
  const test::TempDir tmp("out_bad");
  EXPECT_EQ(error_of([] { check_output_path(""); }), "empty file name");
  EXPECT_EQ(error_of([&] { check_output_path(tmp.root().string()); }),
            tmp.root().string() + ": is a directory");
  EXPECT_NE(error_of([&] { check_output_path(tmp.path("no/such/x.json")); }).find("does not exist"),
            std::string::npos);
  // /proc takes no new files, even from root: the write itself fails, cleanly.
  EXPECT_FALSE(error_of([] { write_output_file("/proc/rt2_test.json", "x"); }).empty());
  EXPECT_FALSE(fs::exists("/proc/rt2_test.json"));
}

TEST(OutputFile, SameFileSeesThroughLinksAndDotSegments) {
  const test::TempDir tmp("out_same");
  write_output_file(tmp.path("a.toml"), "x");
  fs::create_symlink("a.toml", tmp.path("l.toml"));
  EXPECT_TRUE(same_file(tmp.path("a.toml"), tmp.path("l.toml")));
  EXPECT_TRUE(same_file(tmp.path("a.toml"), (tmp.root() / "." / "a.toml").string()));
  EXPECT_TRUE(same_file(tmp.path("new.json"), (tmp.root() / "sub" / ".." / "new.json").string()));
  EXPECT_FALSE(same_file(tmp.path("a.toml"), tmp.path("b.toml")));
}

// Death tests re-run this test binary for just one test ("threadsafe" style), so the child
// has no other threads and no libraries whose exit handlers could wait for them.
// The child opens a TemporaryFile beside `target`, says so on stderr, then ends by `end`.
template <class End>
void temporary_file_then(const std::string& target, End&& end) {
  TemporaryFile tmp(target, target);
  tmp.write("partial");
  std::fprintf(stderr, "opened %s\n", tmp.path().c_str());
  end();
}

TEST(OutputFile, ASignalRemovesTheTemporaryFileAndStillEndsTheProcess) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const test::TempDir tmp("out_signal");
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    EXPECT_EXIT(temporary_file_then(tmp.path("img.png"), [&] { ::raise(sig); }),
                ::testing::KilledBySignal(sig), "opened .*img.tmp[0-9]+.png")
        << "signal " << sig;
    EXPECT_EQ(entries(tmp.root()), 0u) << "signal " << sig;
  }
}

TEST(OutputFile, ExitFromALibraryRemovesTheTemporaryFile) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const test::TempDir tmp("out_exit");
  EXPECT_EXIT(temporary_file_then(tmp.path("img.jpg"), [] { std::exit(3); }),  // as libjpeg does
              ::testing::ExitedWithCode(3), "opened .*img.tmp[0-9]+.jpg");
  EXPECT_EQ(entries(tmp.root()), 0u);
}

}  // namespace
}  // namespace rt2::io
