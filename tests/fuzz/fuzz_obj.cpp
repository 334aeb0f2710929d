// tests/fuzz/fuzz_obj.cpp — libFuzzer target for OBJ meshes and their MTL library: each
// input is split into an OBJ part and an optional MTL part, written to <scratch>/mesh.obj
// and <scratch>/mesh.mtl, and mesh.obj is loaded with rt2::load_scene (a bare OBJ, framed).
//
// The split: everything before the first line "#MTL" is the OBJ; everything after that line
// is the MTL. "#MTL" is an OBJ comment, so an input is still a plain OBJ to any other tool.
// Without the line there is no mesh.mtl (it is removed), which exercises the "library not
// found" path. The OBJ names the library itself ("mtllib mesh.mtl"), so a mutated name is a
// missing library, and "mtllib mesh.obj" makes the OBJ its own MTL. scripts/fuzz builds
// seeds in this form from the OBJ/MTL pairs of scenes/ and tests/hostile/.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string_view>
#include <system_error>

#include "tests/fuzz/fuzz_io.h"

namespace {

constexpr std::string_view kSeparator = "\n#MTL\n";

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  rt2::fuzz::silence_warnings();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fs = std::filesystem;
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const fs::path& dir = rt2::fuzz::scratch("obj");
  const std::size_t cut = input.find(kSeparator);
  rt2::fuzz::write_file(dir / "mesh.obj", input.substr(0, cut));
  std::error_code ec;
  if (cut == std::string_view::npos)
    fs::remove(dir / "mesh.mtl", ec);
  else
    rt2::fuzz::write_file(dir / "mesh.mtl", input.substr(cut + kSeparator.size()));
  rt2::fuzz::load(dir / "mesh.obj");
  return 0;
}
