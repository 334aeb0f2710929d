// tests/fuzz/fuzz_scene.cpp — libFuzzer target for TOML scene files: each input is written
// byte for byte to <scratch>/input.toml and loaded with rt2::load_scene.
//
// So that [[meshes]] entries lead somewhere, the OBJ and MTL files of scenes/ and
// tests/hostile/ (those of at most 64 KiB) are copied into the scratch folder once, at start:
// a seed such as scenes/cornell.toml (file = "cornell_room.obj") then loads its real mesh, and
// mutations of it reach the OBJ and MTL code as well. Everything else is in fuzz_io.h. Built
// and run by scripts/fuzz (--target toml).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <system_error>

#include "tests/fuzz/fuzz_io.h"

#ifndef RT2_SOURCE_DIR
#error "scripts/fuzz defines RT2_SOURCE_DIR as the repository root"
#endif

namespace {

namespace fs = std::filesystem;

constexpr std::uintmax_t kMaxCompanionBytes = 64 * 1024;

// Copies the small regular .obj and .mtl files of `folder` into `to`.
void copy_companions(const fs::path& folder, const fs::path& to) {
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(folder, ec)) {
    const std::string ext = e.path().extension().string();
    if ((ext != ".obj" && ext != ".mtl") || !e.is_regular_file(ec) || e.is_symlink(ec)) continue;
    if (e.file_size(ec) > kMaxCompanionBytes) continue;
    fs::copy_file(e.path(), to / e.path().filename(), fs::copy_options::overwrite_existing, ec);
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  rt2::fuzz::silence_warnings();
  const fs::path& dir = rt2::fuzz::scratch("toml");
  copy_companions(fs::path(RT2_SOURCE_DIR) / "scenes", dir);
  copy_companions(fs::path(RT2_SOURCE_DIR) / "tests" / "hostile", dir);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const fs::path path = rt2::fuzz::scratch("toml") / "input.toml";
  rt2::fuzz::write_file(path, std::string_view(reinterpret_cast<const char*>(data), size));
  rt2::fuzz::load(path);
  return 0;
}
