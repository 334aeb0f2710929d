// tests/fuzz/fuzz_gltf.cpp — libFuzzer target for glTF 2.0 files: the input's first byte
// chooses the file name (even: <scratch>/scene.gltf, odd: <scratch>/scene.glb), the rest is
// the file, loaded with rt2::load_scene. The loader tells JSON from binary by the content
// ("glTF" first), so either name reaches either parser; the name only chooses the dispatch.
// Seeds (scripts/fuzz) are the .gltf and .glb files of tests/hostile/ and scenes/, each with
// the byte that names it so. Files that the seeds' URIs name (buffers, images) are absent
// unless a mutation names the input itself or the scratch folder.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "tests/fuzz/fuzz_io.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  rt2::fuzz::silence_warnings();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string_view input(reinterpret_cast<const char*>(data) + 1, size - 1);
  const auto& dir = rt2::fuzz::scratch("gltf");
  const auto path = dir / (data[0] % 2 ? "scene.glb" : "scene.gltf");
  rt2::fuzz::write_file(path, input);
  rt2::fuzz::load(path);
  return 0;
}
