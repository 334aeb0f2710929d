// tests/rt2/small_file_system.h — a real, nearly full disk for the tests of failed writes:
// a 64 KiB tmpfs mounted on a fresh folder, unmounted when the object goes. Mounting needs
// root (and a system that allows it); otherwise `available()` is false and `why_not()`
// says why, for GTEST_SKIP.
#pragma once

#include <sys/mount.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "tests/rt2/temp_dir.h"

namespace rt2::test {

class SmallFileSystem {
 public:
  explicit SmallFileSystem(const char* size = "64k") : dir_("tmpfs") {
    if (::geteuid() != 0) {
      why_not_ = "mounting a small tmpfs needs root";
      return;
    }
    const std::string options = std::string("size=") + size;
    if (::mount("tmpfs", dir_.root().c_str(), "tmpfs", 0, options.c_str()) != 0) {
      why_not_ = std::string("mount -t tmpfs failed: ") + std::strerror(errno);
      return;
    }
    mounted_ = true;
  }
  ~SmallFileSystem() {
    if (mounted_) ::umount2(dir_.root().c_str(), MNT_DETACH);
  }
  SmallFileSystem(const SmallFileSystem&) = delete;
  SmallFileSystem& operator=(const SmallFileSystem&) = delete;

  bool available() const { return mounted_; }
  const std::string& why_not() const { return why_not_; }
  std::string path(const std::string& name) const { return dir_.path(name); }
  // Every name in the file system (hidden temporary files included).
  std::size_t entries() const {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir_.root())) ++n;
    return n;
  }

 private:
  TempDir dir_;
  bool mounted_ = false;
  std::string why_not_;
};

}  // namespace rt2::test
