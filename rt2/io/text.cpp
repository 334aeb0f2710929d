// rt2/io/text.cpp — the message and file helpers shared by the scene loaders (internal; see
// rt2/io/text.h): one-line messages with file:line:col locations, "did you mean" hints, whole
// files read with a size limit, and the line and token splitting of OBJ and MTL text.
#include "rt2/io/text.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string_view>
#include <system_error>
#include <vector>

#include "rt2/base/error.h"
#include "rt2/scene/scene.h"

namespace rt2::io {
namespace {

namespace fs = std::filesystem;

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

}  // namespace

// ---- messages ---------------------------------------------------------------------------

std::string one_line(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (c > ' ' && c != 0x7f)
      out += ch;
    else if (!out.empty() && out.back() != ' ')
      out += ' ';
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

std::string fmt(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string location(const std::string& file, std::size_t line, std::size_t column) {
  std::string s = file;
  if (line > 0) s += ":" + std::to_string(line);
  if (line > 0 && column > 0) s += ":" + std::to_string(column);
  return s;
}

[[noreturn]] void error_at(const std::string& file, std::size_t line, std::size_t column,
                           const std::string& msg) {
  throw Error(one_line(location(file, line, column) + ": " + msg));
}

namespace {
thread_local int warnings_off = 0;
}  // namespace

void warn(const std::string& msg) {
  if (warnings_off == 0) std::cerr << "warning: " << one_line(msg) << '\n';
}

WarningsOff::WarningsOff() { ++warnings_off; }
WarningsOff::~WarningsOff() { --warnings_off; }

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

std::size_t common_prefix(std::string_view a, std::string_view b) {
  std::size_t n = 0;
  while (n < a.size() && n < b.size() && a[n] == b[n]) ++n;
  return n;
}

void validate(const std::string& file, const Scene& scene) {
  try {
    scene.validate();
  } catch (const Error& e) {
    throw Error(one_line(file + ": " + e.what()));
  }
}

// ---- files ------------------------------------------------------------------------------

namespace {

// read_file and read_text_file: `text` adds the checks of read_text_file.
std::string read_whole(const std::string& path, std::size_t max_bytes, const std::string& context,
                       bool text) {
  const auto where = [&](std::size_t line) {
    return context.empty() ? location(path, line, 0) : context + " '" + path + "'";
  };
  auto fail_read = [&](const std::string& why, std::size_t line = 0) {
    throw Error(one_line(
        where(line) + ": " +
        (context.empty() || line == 0 ? why : why + " (line " + std::to_string(line) + ")")));
  };
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (st.type() == fs::file_type::not_found) fail_read("file not found");
  if (st.type() == fs::file_type::none) fail_read("cannot access: " + ec.message());
  if (st.type() == fs::file_type::directory) fail_read("is a directory, not a file");
  // Devices and pipes (/dev/zero) are refused: they need not end.
  if (st.type() != fs::file_type::regular) fail_read("is not a regular file");

  // A regular file yields the size it reports. Those of /proc and /sys report 0 (or a
  // guess) and yield more, some without end (/proc/self/pagemap is terabytes): the limit
  // would stop them only after max_bytes of memory, so they are refused as soon as they
  // pass the size they report.
  const std::uintmax_t reported = fs::file_size(path, ec);
  if (ec) fail_read("cannot access: " + ec.message());
  const auto too_large = [&] {
    fail_read("is larger than " + std::to_string(max_bytes >> 20) + " MiB");
  };
  if (reported > max_bytes) too_large();
  errno = 0;
  const std::unique_ptr<std::FILE, FileCloser> f(std::fopen(path.c_str(), "rb"));
  if (!f) fail_read(std::string("cannot open: ") + std::strerror(errno));
  std::string out;
  if (!text) out.reserve(static_cast<std::size_t>(reported));
  std::vector<char> buf(std::size_t{1} << 16);
  std::size_t n;
  while ((n = std::fread(buf.data(), 1, buf.size(), f.get())) > 0) {
    if (out.size() + n > max_bytes) too_large();
    if (out.size() + n > reported)
      fail_read("is not an ordinary file: it holds more than the " + std::to_string(reported) +
                " bytes it reports (a /proc or /sys file, or one being written)");
    const std::string_view chunk(buf.data(), n);
    if (text && out.empty()) {
      const std::string kind = not_text(chunk);
      if (!kind.empty()) fail_read("file is " + kind);
      out.reserve(static_cast<std::size_t>(reported));  // only now: it may be text
    }
    if (text) {
      const std::size_t nul = chunk.find('\0');
      if (nul != std::string_view::npos) {
        const std::string_view before = chunk.substr(0, nul);
        const std::size_t line =
            1 + static_cast<std::size_t>(std::count(out.begin(), out.end(), '\n') +
                                         std::count(before.begin(), before.end(), '\n'));
        fail_read("file contains a NUL byte: it is binary or UTF-16, but it must be text", line);
      }
    }
    out.append(chunk);
  }
  if (std::ferror(f.get())) fail_read(std::string("cannot read: ") + std::strerror(errno));
  return out;
}

}  // namespace

std::string read_file(const std::string& path, std::size_t max_bytes, const std::string& context) {
  return read_whole(path, max_bytes, context, false);
}

std::string read_text_file(const std::string& path, std::size_t max_bytes,
                           const std::string& context) {
  return read_whole(path, max_bytes, context, true);
}

std::string not_text(std::string_view head) {
  struct Signature {
    std::string_view bytes;
    const char* what;
  };
  using namespace std::string_view_literals;
  static constexpr Signature kSignatures[] = {
      {"\x1F\x8B"sv, "gzip-compressed; decompress it first (gunzip)"},
      {"\xFD\x37zXZ\0"sv, "xz-compressed; decompress it first (unxz)"},
      {"\x28\xB5\x2F\xFD"sv, "zstd-compressed; decompress it first (unzstd)"},
      {"PK\x03\x04"sv, "a ZIP archive; extract the file from it first (unzip)"},
      {"7z\xBC\xAF\x27\x1C"sv, "a 7-Zip archive; extract the file from it first"},
      {"\x00\x00\xFE\xFF"sv, "UTF-32 (it starts with a UTF-32 byte-order mark); save it as UTF-8"},
      {"\xFF\xFE\x00\x00"sv, "UTF-32 (it starts with a UTF-32 byte-order mark); save it as UTF-8"},
      {"\xFF\xFE"sv, "UTF-16 (it starts with a UTF-16 byte-order mark); save it as UTF-8"},
      {"\xFE\xFF"sv, "UTF-16 (it starts with a UTF-16 byte-order mark); save it as UTF-8"},
  };
  for (const Signature& s : kSignatures)
    if (head.starts_with(s.bytes)) return s.what;
  // "BZh", the block size, and the first block's magic number (a text could start "BZh").
  if (head.size() >= 10 && head.starts_with("BZh") && head[3] >= '1' && head[3] <= '9' &&
      head.substr(4, 6) == "1AY&SY")
    return "bzip2-compressed; decompress it first (bunzip2)";
  return {};
}

std::pair<std::size_t, std::size_t> line_and_column(std::string_view text, std::size_t pos) {
  const std::string_view before = text.substr(0, pos);
  const std::size_t line =
      1 + static_cast<std::size_t>(std::count(before.begin(), before.end(), '\n'));
  const std::size_t nl = before.rfind('\n');
  std::string_view line_text = before.substr(nl == std::string_view::npos ? 0 : nl + 1);
  if (nl == std::string_view::npos) line_text = without_bom(line_text);
  // Characters, as toml++ counts them: every byte but UTF-8 continuation bytes (10xxxxxx).
  const auto continuation = std::count_if(line_text.begin(), line_text.end(), [](char c) {
    return (static_cast<unsigned char>(c) & 0xC0) == 0x80;
  });
  return {line, line_text.size() - static_cast<std::size_t>(continuation) + 1};
}

// ---- lines and tokens -------------------------------------------------------------------

std::string_view after_keyword(std::string_view line) {
  const std::size_t end = line.find_first_of(" \t");
  if (end == std::string_view::npos) return {};
  const std::size_t name = line.find_first_not_of(" \t", end);
  return name == std::string_view::npos ? std::string_view() : line.substr(name);
}

std::string_view without_bom(std::string_view text) {
  return text.starts_with(kUtf8Bom) ? text.substr(kUtf8Bom.size()) : text;
}

std::vector<std::string_view> split_blanks(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while ((i = s.find_first_not_of(" \t", i)) != std::string_view::npos) {
    const std::size_t end = std::min(s.find_first_of(" \t", i), s.size());
    out.push_back(s.substr(i, end - i));
    i = end;
  }
  return out;
}

bool huge_exponent(std::string_view token) {
  const std::size_t start = token.find_first_not_of("+-");
  if (start > 1) return false;  // tinyobjloader reads one sign at most
  std::size_t i = token.find_first_not_of("0123456789.", start);
  if (i == std::string_view::npos || i == start || (token[i] != 'e' && token[i] != 'E'))
    return false;
  i = token.find_first_not_of("+-", i + 1);
  i = token.find_first_not_of('0', i);  // leading zeros do not grow tinyobjloader's int
  if (i == std::string_view::npos) return false;
  const std::size_t end = std::min(token.find_first_not_of("0123456789", i), token.size());
  return end - i >= 10;
}

void check_exponents(const std::string& file, std::size_t line,
                     std::span<const std::string_view> tokens) {
  for (const std::string_view token : tokens)
    if (huge_exponent(token))
      error_at(file, line, 0,
               "number '" + std::string(token) + "' has an exponent of 10 digits or more");
}

bool parse_double(std::string_view token, double& v) {
  const std::string s(token);  // strtod needs the terminator; it also reads nan and inf
  char* end = nullptr;
  v = std::strtod(s.c_str(), &end);
  return !s.empty() && end == s.c_str() + s.size();
}

}  // namespace rt2::io
