// rt2/io/text.h — the message and file helpers shared by the scene loaders (internal).
//
// Part of the implementation of rt2/io/scene_io.h, used only by rt2/io/scene_io.cpp and rt2/io/;
// not an API. Every message the loaders produce is built here: one line, starting with
// "file", "file:line" or "file:line:column", numbers in shortest round-trip form, with a
// "did you mean" hint for a misspelt key or name. Files are read whole, with a size limit
// and a message for each way a path can fail; OBJ and MTL text is walked line by line and
// split into blank-separated tokens as tinyobjloader does.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace rt2 {
struct Scene;
}

namespace rt2::io {

// ---- messages ---------------------------------------------------------------------------

// `s` with control characters (newlines in toml++ and tinyobjloader messages, or in a quoted
// TOML key) turned into spaces and runs of spaces collapsed, so what() is one line.
std::string one_line(std::string_view s);

// Shortest round-trip form: -1, 0.25, 1e+16, nan, inf.
std::string fmt(double v);

// "file", "file:line" or "file:line:column" (a line or column of 0 is unknown).
std::string location(const std::string& file, std::size_t line, std::size_t column);

// Throws rt2::Error "location: msg" (see location), made one line.
[[noreturn]] void error_at(const std::string& file, std::size_t line, std::size_t column,
                           const std::string& msg);

// Prints "warning: msg" to stderr, made one line (nothing while a WarningsOff lives on
// this thread).
void warn(const std::string& msg);

// While one exists, warn() prints nothing on this thread: for a second reading of a file
// whose first reading has warned.
class WarningsOff {
 public:
  WarningsOff();
  ~WarningsOff();
  WarningsOff(const WarningsOff&) = delete;
  WarningsOff& operator=(const WarningsOff&) = delete;
};

// Levenshtein distance, for "did you mean" hints (keys and names are short).
std::size_t edit_distance(std::string_view a, std::string_view b);

// The number of leading characters `a` and `b` share.
std::size_t common_prefix(std::string_view a, std::string_view b);

// " (did you mean 'radius'?)" for the closest candidate that is within two edits or shares
// the first four letters (rotation: rotate), else "".
template <class Names>
std::string suggestion(std::string_view wrong, const Names& candidates) {
  if (wrong.size() > 64) return "";  // not a typo; and the distance is quadratic
  std::string_view best;
  std::size_t best_d = std::string_view::npos;
  for (const auto& c : candidates) {
    const std::string_view name(c);
    const std::size_t d = edit_distance(wrong, name);
    const bool close = (d <= 2 && d < name.size()) || common_prefix(wrong, name) >= 4;
    if (close && d < best_d) {
      best_d = d;
      best = c;
    }
  }
  return best.empty() ? "" : " (did you mean '" + std::string(best) + "'?)";
}

// Scene::validate(), its message prefixed with `file` ("file: ...") and made one line.
void validate(const std::string& file, const Scene& scene);

// ---- files ------------------------------------------------------------------------------

// The whole of the regular file `path` (not a device, pipe or /proc file: those need not end),
// at most `max_bytes`. `context` is empty when the user named `path`
// directly (the message starts with it), or "scene.toml:7:8: meshes[0].file" when another
// file names it (the message starts with that, and quotes the path).
std::string read_file(const std::string& path, std::size_t max_bytes, const std::string& context);

// As read_file, for a file that must be text (OBJ, MTL): refused as soon as it shows it is
// not — a compressed file or an archive, a UTF-16 or UTF-32 byte-order mark at its start, a
// NUL byte anywhere (named with its line) — so that a 2 GB file of zeros costs one read of
// 64 KiB, not 2 GB of memory.
std::string read_text_file(const std::string& path, std::size_t max_bytes,
                           const std::string& context);

// What a file starting with `head` is when it is certainly not text (by its signature: gzip,
// bzip2, xz, zstd, ZIP, 7-Zip, a UTF-16 or UTF-32 byte-order mark), as the rest of a message
// "file is ...", e.g. "gzip-compressed; decompress it first (gunzip)"; "" when it may be
// text.
std::string not_text(std::string_view head);

// 1-based line and column of byte `pos` in `text`. The column counts UTF-8 characters (not
// bytes) and not a byte-order mark, as toml++ does, so that both report the same places.
std::pair<std::size_t, std::size_t> line_and_column(std::string_view text, std::size_t pos);

// ---- lines and tokens -------------------------------------------------------------------

// Calls fn(line_number, line) for each line of `text`, split at \n, \r\n or a lone \r as
// tinyobjloader splits it, with blanks trimmed at both ends.
template <class Fn>
void for_each_line(std::string_view text, Fn&& fn) {
  std::size_t line = 0, i = 0;
  while (i < text.size()) {
    std::size_t end = text.find_first_of("\r\n", i);
    if (end == std::string_view::npos) end = text.size();
    std::string_view s = text.substr(i, end - i);
    const std::size_t first = s.find_first_not_of(" \t");
    s = first == std::string_view::npos ? std::string_view()
                                        : s.substr(first, s.find_last_not_of(" \t") - first + 1);
    fn(++line, s);
    i = end + (text.substr(end, 2) == "\r\n" ? 2 : 1);
  }
}

// `line` (blanks trimmed at both ends, as for_each_line gives it) without its first token and
// the blanks after it: the name in "usemtl Hard Wood" or "newmtl  red" ("Hard Wood", "red").
std::string_view after_keyword(std::string_view line);

// The UTF-8 byte-order mark that Windows editors write at the start of a text file.
inline constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";

// `text` without a leading kUtf8Bom (tinyobjloader would take it for part of the first
// line's keyword, and drop that line).
std::string_view without_bom(std::string_view text);

// The blank-separated (spaces, tabs) tokens of `s`.
std::vector<std::string_view> split_blanks(std::string_view s);

// Whether `token` is a number (as tinyobjloader reads one: sign, digits, '.', 'e') whose
// exponent has 10 or more significant digits. tinyobjloader's tryParseDouble overflows an int
// on some of those (1e2147483648: undefined behaviour); none is a sensible number, so the OBJ
// and MTL scans refuse them all before tinyobjloader sees them.
bool huge_exponent(std::string_view token);

// Refuses (throws rt2::Error at `file`:`line`) the first of `tokens` that huge_exponent flags.
void check_exponents(const std::string& file, std::size_t line,
                     std::span<const std::string_view> tokens);

// The whole token as a number, or false.
bool parse_double(std::string_view token, double& v);

}  // namespace rt2::io
