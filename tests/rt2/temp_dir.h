// tests/rt2/temp_dir.h — a fresh folder under the system's temporary folder for a test's
// files, removed with its contents when the TempDir goes.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <string_view>
#include <system_error>

namespace rt2::test {

class TempDir {
 public:
  // `tag` names the folder (rt2_<tag>_<pid>_<random>), to tell whose it is if one is left.
  explicit TempDir(const std::string& tag = "test") {
    std::random_device random;
    root_ = std::filesystem::temp_directory_path() /
            ("rt2_" + tag + "_" + std::to_string(::getpid()) + "_" + std::to_string(random()));
    std::filesystem::create_directories(root_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(root_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& root() const { return root_; }
  std::string path(const std::string& name) const { return (root_ / name).string(); }
  // Writes `content` byte for byte to `name` (folders created) and returns its path.
  std::string write(const std::string& name, std::string_view content) const {
    const std::filesystem::path p = root_ / name;
    std::filesystem::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary).write(content.data(), std::streamsize(content.size()));
    return p.string();
  }

 private:
  std::filesystem::path root_;
};

}  // namespace rt2::test
