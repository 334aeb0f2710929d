// rt2/image/file_screen.cpp — the byte-level checks of image files (see file_screen.h).
#include "rt2/image/file_screen.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <string>
#include <utility>

namespace rt2 {

namespace {

constexpr int kEnd = std::char_traits<char>::eof();

// The scans (SOS segments) of the JPEG in `bytes` (after its first two bytes), counted up
// to `most` + 1 by walking its marker segments; entropy-coded data is skipped to the next
// marker (0xFF followed by neither 0 nor a restart marker).
int jpeg_scans(std::streambuf& bytes, int most) {
  int scans = 0;
  for (int c = bytes.sbumpc(); c != kEnd; c = bytes.sbumpc()) {
    if (c != 0xFF) continue;
    int marker = bytes.sbumpc();
    while (marker == 0xFF) marker = bytes.sbumpc();
    if (marker == kEnd || marker == 0xD9) break;                                 // EOI
    if (marker == 0 || marker == 1 || (marker >= 0xD0 && marker <= 0xD7)) continue;  // no length
    const int hi = bytes.sbumpc(), lo = bytes.sbumpc();
    if (lo == kEnd) break;
    if (marker == 0xDA && ++scans > most) break;
    bytes.pubseekoff((hi << 8 | lo) - 2, std::ios::cur);
  }
  return scans;
}

// Little-endian integers of an OpenEXR header; false at the end of the file.
bool read_le(std::streambuf& bytes, std::uint32_t& v) {
  unsigned char b[4];
  if (bytes.sgetn(reinterpret_cast<char*>(b), 4) != 4) return false;
  v = std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 |
      std::uint32_t(b[3]) << 24;
  return true;
}

// A 0-terminated string of at most `most` characters; false if longer or at the end.
bool read_name(std::streambuf& bytes, std::size_t most, std::string& s) {
  s.clear();
  for (int c = bytes.sbumpc(); c != 0; c = bytes.sbumpc()) {
    if (c == kEnd || s.size() == most) return false;
    s += char(c);
  }
  return true;
}

// `s` with every byte outside printable ASCII as '?', for a one-line message.
std::string printable(std::string s) {
  for (char& c : s)
    if (c < 0x20 || c > 0x7E) c = '?';
  return s;
}

// The bytes OpenEXR 3.1 reads for the value of an attribute of type `type` and declared
// size `size`: most types read a fixed number whatever the size says, a channel list reads
// to its end marker (-1 here: walk it), the others read `size`.
std::int64_t exr_value_bytes(const std::string& type, std::uint32_t size) {
  static const std::pair<const char*, int> kFixed[] = {
      {"box2i", 16}, {"box2f", 16}, {"chromaticities", 32}, {"compression", 1},
      {"deepImageState", 1}, {"double", 8}, {"envmap", 1}, {"float", 4}, {"int", 4},
      {"keycode", 28}, {"lineOrder", 1}, {"m33f", 36}, {"m33d", 72}, {"m44f", 64},
      {"m44d", 128}, {"rational", 8}, {"tiledesc", 9}, {"timecode", 8}, {"v2i", 8},
      {"v2f", 8}, {"v2d", 16}, {"v3i", 12}, {"v3f", 12}, {"v3d", 24}};
  for (const auto& [name, bytes] : kFixed)
    if (type == name) return bytes;
  if (type == "chlist") return -1;
  if (type == "floatvector") return size / 4 * 4;
  return size;
}

// Skips a channel list as OpenEXR reads it: entries of a name and 16 bytes, to an empty name.
bool skip_channel_list(std::streambuf& bytes) {
  std::string name;
  for (;;) {
    if (!read_name(bytes, 255, name)) return false;
    if (name.empty()) return true;
    bytes.pubseekoff(16, std::ios::cur);
  }
}

// The OpenEXR file in `bytes` (after its 4-byte magic number) of `file_bytes` bytes, read
// as OpenEXR 3.1 reads its headers: every attribute's declared size fits in the file.
std::string screen_exr(std::streambuf& bytes, std::uint64_t file_bytes) {
  std::uint32_t version = 0;
  if (!read_le(bytes, version)) return "";
  const bool multipart = version & 0x1000;
  // OpenEXR reads names of up to 255 characters whatever the version's long-names flag says
  constexpr std::size_t most = 255;
  std::string name, type;
  for (;;) {  // parts
    if (multipart && bytes.sgetc() == 0) break;  // the empty header that ends the list
    for (;;) {  // attributes
      if (!read_name(bytes, most, name) || (!name.empty() && !read_name(bytes, most, type)))
        return "";  // malformed: OpenEXR refuses it
      if (name.empty()) break;
      std::uint32_t size = 0;
      if (!read_le(bytes, size)) return "";
      const auto at = std::uint64_t(bytes.pubseekoff(0, std::ios::cur));
      if (size > file_bytes - std::min(at, file_bytes))
        return "its OpenEXR attribute '" + printable(name) + "' declares " + std::to_string(size) +
               " bytes, more than the file holds";
      const std::int64_t value = exr_value_bytes(type, size);
      if (value < 0 ? !skip_channel_list(bytes) : bytes.pubseekoff(value, std::ios::cur) < 0)
        return "";
    }
    if (!multipart) break;
  }
  return "";
}

// The BMP file in `bytes`: not run-length compressed. OIIO 2.4's reader decodes such a file
// into palette indices whatever its bits per pixel say, and a 24-bit one then crashed it.
std::string screen_bmp(std::streambuf& bytes) {
  bytes.pubseekoff(14, std::ios::beg);
  std::uint32_t info = 0, compression = 0;
  if (!read_le(bytes, info) || info < 40) return "";  // OS/2 headers have no compression
  bytes.pubseekoff(14 + 16, std::ios::beg);
  if (!read_le(bytes, compression)) return "";
  if (compression == 1 || compression == 2)
    return "a run-length compressed BMP, which rt2 does not read";
  return "";
}

}  // namespace

std::string screen_image_file(const std::string& path, std::uint64_t file_bytes) {
  std::ifstream in(path, std::ios::binary);
  std::streambuf& bytes = *in.rdbuf();
  char magic[4] = {};
  if (bytes.sgetn(magic, 4) != 4) return "";
  if (std::memcmp(magic, "\xff\xd8\xff", 3) == 0) {
    bytes.pubseekoff(2, std::ios::beg);
    if (jpeg_scans(bytes, kMaxJpegScans) > kMaxJpegScans)
      return "a JPEG of more than " + std::to_string(kMaxJpegScans) + " scans";
  } else if (std::memcmp(magic, "\x76\x2f\x31\x01", 4) == 0) {
    return screen_exr(bytes, file_bytes);
  } else if (std::memcmp(magic, "BM", 2) == 0) {
    return screen_bmp(bytes);
  }
  return "";
}

}  // namespace rt2
