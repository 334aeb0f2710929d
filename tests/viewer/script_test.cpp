// The viewer's script files (rt2cpr/viewer/script.h): every command with its arguments,
// and every mistake as one line naming the file and line.
#include "rt2cpr/viewer/script.h"

#include <gtest/gtest.h>

#include <string>

#include "rt2/base/error.h"
#include "tests/rt2/error_of.h"
#include "tests/rt2/temp_dir.h"

namespace rt2cpr::viewer {
namespace {

using Op = ScriptCommand::Op;

TEST(Script, ReadsEveryCommandWithItsArguments) {
  rt2::test::TempDir dir("script");
  const std::string path = dir.write("s.txt",
                                     "# a flight\n"
                                     "\n"
                                     "wait 0.5\r\n"
                                     "key W 1.5\n"
                                     "  key F12\n"
                                     "mouse -30 12.5\n"
                                     "scroll -2\n"
                                     "screenshot out/my shot.png  \n"
                                     "window-shot w.png\n"
                                     "wait-still\n"
                                     "wait-still 30\n"
                                     "set depth 8\n"
                                     "resize 320 200\n"
                                     "quit\n");
  const auto s = read_script(path);
  ASSERT_EQ(s.size(), 12u);
  EXPECT_EQ(s[0].op, Op::wait);
  EXPECT_EQ(s[0].seconds, 0.5);
  EXPECT_EQ(s[0].line, 3);
  EXPECT_EQ(s[1].op, Op::key);
  EXPECT_EQ(s[1].name, "W");
  EXPECT_EQ(s[1].seconds, 1.5);
  EXPECT_EQ(s[2].name, "F12");
  EXPECT_EQ(s[2].seconds, 0.0);  // a tap
  EXPECT_EQ(s[3].op, Op::mouse);
  EXPECT_EQ(s[3].x, -30.0);
  EXPECT_EQ(s[3].y, 12.5);
  EXPECT_EQ(s[4].op, Op::scroll);
  EXPECT_EQ(s[4].x, -2.0);
  EXPECT_EQ(s[5].op, Op::screenshot);
  EXPECT_EQ(s[5].name, "out/my shot.png");  // the rest of the line, trailing blanks dropped
  EXPECT_EQ(s[6].op, Op::window_shot);
  EXPECT_EQ(s[7].op, Op::wait_still);
  EXPECT_EQ(s[7].seconds, 600.0);
  EXPECT_EQ(s[8].seconds, 30.0);
  EXPECT_EQ(s[9].op, Op::set);
  EXPECT_EQ(s[9].name, "depth");
  EXPECT_EQ(s[9].value, "8");
  EXPECT_EQ(s[10].op, Op::resize);
  EXPECT_EQ(s[10].x, 320.0);
  EXPECT_EQ(s[11].op, Op::quit);
  EXPECT_EQ(s[11].line, 14);
}

TEST(Script, EveryMistakeIsOneLineWithFileAndLine) {
  rt2::test::TempDir dir("script");
  const struct {
    const char* line;
    const char* says;
  } cases[] = {
      {"jump 3", "unknown command 'jump'"},
      {"wait", "usage: wait SECONDS"},
      {"wait 1 2", "usage: wait SECONDS"},
      {"wait -1", "seconds must be in [0, 86400]"},
      {"wait nan", "seconds must be a number"},
      {"wait 1e999", "seconds must be a number"},
      {"wait 2s", "seconds must be a number"},
      {"key", "usage: key NAME [SECONDS]"},
      {"key W inf", "seconds must be a number"},
      {"mouse 3", "usage: mouse DX DY"},
      {"mouse 1 1e7", "DY must be in"},
      {"screenshot", "usage: screenshot PATH"},
      {"screenshot    ", "usage: screenshot PATH"},
      {"resize 0 100", "W must be in [1, 16384]"},
      {"resize 100 20000", "H must be in [1, 16384]"},
      {"set depth", "usage: set NAME VALUE"},
      {"quit now", "usage: quit"},
  };
  for (const auto& c : cases) {
    const std::string path = dir.write("s.txt", std::string("wait 0\n") + c.line + "\n");
    const std::string e = rt2::test::error_of([&] { read_script(path); });
    EXPECT_EQ(e.rfind(path + ":2: ", 0), 0u) << e;
    EXPECT_NE(e.find(c.says), std::string::npos) << c.line << " -> " << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  }
}

TEST(Script, AMissingFileOrAFolderIsOneLine) {
  rt2::test::TempDir dir("script");
  EXPECT_NE(rt2::test::error_of([&] { read_script(dir.path("none.txt")); }).find("no such file"),
            std::string::npos);
  EXPECT_NE(rt2::test::error_of([&] { read_script(dir.root().string()); }).find("not a regular file"),
            std::string::npos);
}

TEST(Script, AnEmptyScriptIsNoCommands) {
  rt2::test::TempDir dir("script");
  EXPECT_TRUE(read_script(dir.write("s.txt", "")).empty());
  EXPECT_TRUE(read_script(dir.write("t.txt", "# nothing\n\n   \n")).empty());
}

}  // namespace
}  // namespace rt2cpr::viewer
