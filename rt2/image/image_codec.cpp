// rt2/image/image_codec.cpp — finding and loading the image codec library (see image_codec.h).
#include "rt2/image/image_codec.h"

#include <dlfcn.h>

#include <filesystem>
#include <mutex>

#include "rt2/base/error.h"

namespace rt2 {

namespace {

// lib/librt2_image_codec.so beside the running program's bin/ folder.
std::string library_path() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) throw Error("cannot load the image codec: /proc/self/exe: " + ec.message());
  return (exe.parent_path().parent_path() / "lib" / "librt2_image_codec.so").string();
}

const ImageCodec* load() {
  const std::string path = library_path();
  void* lib = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);  // never closed
  if (!lib) throw Error(std::string("cannot load the image codec: ") + ::dlerror());
  using Entry = const ImageCodec* (*)();
  const auto entry = reinterpret_cast<Entry>(::dlsym(lib, "rt2_image_codec"));
  if (!entry) throw Error("cannot load the image codec: " + path + " has no rt2_image_codec");
  return entry();
}

}  // namespace

const ImageCodec& image_codec() {
  static std::mutex m;
  static const ImageCodec* codec = nullptr;
  const std::lock_guard lock(m);
  if (!codec) codec = load();
  return *codec;
}

}  // namespace rt2
