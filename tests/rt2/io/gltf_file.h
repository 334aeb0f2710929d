// tests/rt2/io/gltf_file.h — glTF files built by the tests: a buffer of accessors, written
// as JSON with the buffer as a data: URI or as a binary .glb.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace rt2::test {

inline std::string base64(const std::string& bytes) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const auto a = std::uint8_t(bytes[i]), b = std::uint8_t(bytes[i + 1]),
               c = std::uint8_t(bytes[i + 2]);
    out += {k[a >> 2], k[((a & 3) << 4) | (b >> 4)], k[((b & 15) << 2) | (c >> 6)], k[c & 63]};
  }
  if (i + 1 == bytes.size()) {
    const auto a = std::uint8_t(bytes[i]);
    out += {k[a >> 2], k[(a & 3) << 4], '=', '='};
  } else if (i + 2 == bytes.size()) {
    const auto a = std::uint8_t(bytes[i]), b = std::uint8_t(bytes[i + 1]);
    out += {k[a >> 2], k[((a & 3) << 4) | (b >> 4)], k[(b & 15) << 2], '='};
  }
  return out;
}

// A GLB of `json` and, when not empty, the BIN chunk `bin`: header, JSON chunk
// (space-padded), BIN chunk (zero-padded).
inline std::string glb_of(std::string json, std::string bin) {
  while (json.size() % 4) json += ' ';
  while (bin.size() % 4) bin += '\0';
  const auto u32 = [](std::size_t v) {
    const auto x = std::uint32_t(v);
    std::string s(4, '\0');
    std::memcpy(s.data(), &x, 4);
    return s;
  };
  const std::size_t length = 12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size());
  return "glTF" + u32(2) + u32(length) + u32(json.size()) + "JSON" + json +
         (bin.empty() ? "" : u32(bin.size()) + "BIN" + std::string(1, '\0') + bin);
}

// A glTF file under construction: one buffer, a buffer view and an accessor per array.
class GltfFile {
 public:
  // The buffer as it stands (for tests that build views of their own).
  const std::string& bin() const { return bin_; }
  // Appends raw bytes (4-byte aligned after) and returns their offset.
  std::size_t append(const std::string& bytes) {
    const std::size_t offset = bin_.size();
    bin_ += bytes;
    while (bin_.size() % 4) bin_ += '\0';
    return offset;
  }

  // Appends `values` (4-byte aligned) and returns the new accessor's index.
  template <class T>
  int accessor(const std::vector<T>& values, int component_type, const std::string& type,
               std::size_t count, bool normalized = false) {
    const std::size_t offset = bin_.size();
    bin_.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
    while (bin_.size() % 4) bin_ += '\0';
    const int index = int(accessors_.size());
    views_.push_back(R"({"buffer":0,"byteOffset":)" + std::to_string(offset) + R"(,"byteLength":)" +
                     std::to_string(values.size() * sizeof(T)) + "}");
    accessors_.push_back(R"({"bufferView":)" + std::to_string(index) + R"(,"componentType":)" +
                         std::to_string(component_type) + R"(,"count":)" + std::to_string(count) +
                         R"(,"type":")" + type + "\"" +
                         (normalized ? R"(,"normalized":true)" : "") + "}");
    return index;
  }
  int floats(const std::vector<float>& v, const std::string& type, std::size_t per) {
    return accessor(v, 5126, type, v.size() / per);
  }

  // The JSON, with `rest` (more top-level members, starting with a comma; without "nodes",
  // one node of mesh 0 is added) and the buffer as a data: URI (or, `glb`, without a URI:
  // the GLB's binary chunk).
  std::string json(std::string rest, bool glb = false) const {
    if (rest.find("\"nodes\"") == std::string::npos)
      rest += R"(,"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}])";
    std::string s =
        R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":)" + std::to_string(bin_.size()) +
        (glb ? "" : R"(,"uri":"data:application/octet-stream;base64,)" + base64(bin_) + "\"") +
        R"(}],"bufferViews":[)";
    for (std::size_t i = 0; i < views_.size(); ++i) s += (i ? "," : "") + views_[i];
    s += R"(],"accessors":[)";
    for (std::size_t i = 0; i < accessors_.size(); ++i) s += (i ? "," : "") + accessors_[i];
    return s + "]" + rest + "}";
  }

  // The binary form (glb_of).
  std::string glb(const std::string& rest) const;

 private:
  std::string bin_;
  std::vector<std::string> views_, accessors_;
};

inline std::string GltfFile::glb(const std::string& rest) const {
  return glb_of(json(rest, true), bin_);
}

}  // namespace rt2::test
