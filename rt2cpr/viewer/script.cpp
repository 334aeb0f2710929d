// rt2cpr/viewer/script.cpp — parsing the viewer's script files.
#include "rt2cpr/viewer/script.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "rt2/base/error.h"

namespace rt2cpr::viewer {

namespace {

using Op = ScriptCommand::Op;

struct Syntax {
  Op op;
  int min_args, max_args;
  const char* usage;
};

const std::map<std::string, Syntax>& commands() {
  static const std::map<std::string, Syntax> c = {
      {"wait", {Op::wait, 1, 1, "wait SECONDS"}},
      {"key", {Op::key, 1, 2, "key NAME [SECONDS]"}},
      {"mouse", {Op::mouse, 2, 2, "mouse DX DY"}},
      {"scroll", {Op::scroll, 1, 1, "scroll STEPS"}},
      {"screenshot", {Op::screenshot, 1, 1, "screenshot PATH"}},
      {"window-shot", {Op::window_shot, 1, 1, "window-shot PATH"}},
      {"wait-still", {Op::wait_still, 0, 1, "wait-still [SECONDS]"}},
      {"set", {Op::set, 2, 2, "set NAME VALUE"}},
      {"resize", {Op::resize, 2, 2, "resize W H"}},
      {"quit", {Op::quit, 0, 0, "quit"}},
  };
  return c;
}

class LineError {
 public:
  LineError(const std::string& path, int line) : where_(path + ":" + std::to_string(line) + ": ") {}
  [[noreturn]] void operator()(const std::string& msg) const { throw rt2::Error(where_ + msg); }

 private:
  std::string where_;
};

double number(const std::string& text, double lo, double hi, const char* what, const LineError& fail) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v))
    fail(std::string(what) + " must be a number, got '" + text + "'");
  if (v < lo || v > hi) {
    std::ostringstream m;
    m << what << " must be in [" << lo << ", " << hi << "], got " << text;
    fail(m.str());
  }
  return v;
}

}  // namespace

std::vector<ScriptCommand> read_script(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw rt2::Error(path + ": " + (std::filesystem::exists(path, ec) ? "not a regular file"
                                                                         : "no such file"));
  std::ifstream in(path);
  if (!in) throw rt2::Error(path + ": cannot be read");
  std::vector<ScriptCommand> script;
  std::string text;
  for (int n = 1; std::getline(in, text); ++n) {
    if (n > 1'000'000 || text.size() > 4096)
      throw rt2::Error(path + ":" + std::to_string(n) + ": a script line is at most 4096 "
                       "characters and a script at most 1000000 lines");
    const LineError fail(path, n);
    if (!text.empty() && text.back() == '\r') text.pop_back();
    std::istringstream words(text);
    std::string word;
    std::vector<std::string> args;
    if (!(words >> word) || word[0] == '#') continue;
    // A path may hold blanks: screenshot and window-shot take the rest of the line.
    const auto found = commands().find(word);
    if (found == commands().end())
      fail("unknown command '" + word + "' (expected wait, key, mouse, scroll, screenshot, "
           "window-shot, wait-still, set, resize or quit)");
    const Syntax& syntax = found->second;
    ScriptCommand c;
    c.op = syntax.op;
    c.line = n;
    if (c.op == Op::screenshot || c.op == Op::window_shot) {
      std::string rest;
      std::getline(words >> std::ws, rest);
      while (!rest.empty() && (rest.back() == ' ' || rest.back() == '\t')) rest.pop_back();
      if (rest.empty()) fail(std::string("usage: ") + syntax.usage);
      c.name = rest;
      script.push_back(c);
      continue;
    }
    for (std::string a; words >> a;) args.push_back(a);
    if (int(args.size()) < syntax.min_args || int(args.size()) > syntax.max_args)
      fail(std::string("usage: ") + syntax.usage);
    switch (c.op) {
      case Op::wait: c.seconds = number(args[0], 0, 86400, "seconds", fail); break;
      case Op::key:
        c.name = args[0];
        if (args.size() > 1) c.seconds = number(args[1], 0, 86400, "seconds", fail);
        break;
      case Op::mouse:
        c.x = number(args[0], -1e6, 1e6, "DX", fail);
        c.y = number(args[1], -1e6, 1e6, "DY", fail);
        break;
      case Op::scroll: c.x = number(args[0], -1e6, 1e6, "STEPS", fail); break;
      case Op::wait_still:
        c.seconds = args.empty() ? 600.0 : number(args[0], 0, 86400, "seconds", fail);
        break;
      case Op::set:
        c.name = args[0];
        c.value = args[1];
        break;
      case Op::resize:
        c.x = number(args[0], 1, 16384, "W", fail);
        c.y = number(args[1], 1, 16384, "H", fail);
        break;
      case Op::screenshot:
      case Op::window_shot:
      case Op::quit: break;
    }
    script.push_back(c);
  }
  if (in.bad()) throw rt2::Error(path + ": cannot be read");
  return script;
}

}  // namespace rt2cpr::viewer
