// rt2/image/output_file.cpp — checked, atomic file output (see output_file.h).
#include "rt2/image/output_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <stdexcept>

#include "rt2/base/error.h"

namespace rt2::io {

namespace fs = std::filesystem;

namespace {

// ---- removal of the registered temporary file on a signal or exit() ----------------------
// Written only by TemporaryFile on the thread that writes; read by the handlers, which use
// nothing but unlink, signal and raise (async-signal-safe).
char g_registered[4096];
volatile std::sig_atomic_t g_has_registered = 0;

void remove_registered() {
  if (g_has_registered) ::unlink(g_registered);
}

extern "C" void on_fatal_signal(int sig) {
  remove_registered();
  ::signal(sig, SIG_DFL);
  ::raise(sig);  // delivered when this handler returns: the default action ends the process
}

extern "C" void on_exit_handler() { remove_registered(); }

void install_handlers_once() {
  static std::once_flag once;
  std::call_once(once, [] {
    std::atexit(on_exit_handler);
    for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGABRT}) {
      struct sigaction old {};
      if (::sigaction(sig, nullptr, &old) != 0 || old.sa_handler != SIG_DFL) continue;  // ignored
      struct sigaction sa {};                                  // (nohup) or handled by someone else
      sa.sa_handler = on_fatal_signal;
      sigemptyset(&sa.sa_mask);
      ::sigaction(sig, &sa, nullptr);
    }
  });
}

std::string errno_text(int err) { return std::strerror(err); }

[[noreturn]] void cannot_write(const std::string& path, const std::string& why) {
  throw Error("cannot write " + path + ": " + why);
}

// `path` with every symbolic link along its last component followed (a dangling link gives
// the path it points to): writing replaces that file and leaves the links as they are.
fs::path resolve_links(const std::string& path) {
  fs::path p(path);
  for (int hops = 0; hops < 40; ++hops) {
    std::error_code ec;
    if (!fs::is_symlink(p, ec)) return p;
    const fs::path to = fs::read_symlink(p, ec);
    if (ec) throw Error(path + ": " + ec.message());
    p = to.is_absolute() ? to : p.parent_path() / to;
  }
  throw Error(path + ": too many levels of symbolic links");
}

fs::path folder_of(const fs::path& p) {
  return p.parent_path().empty() ? fs::path(".") : p.parent_path();
}

enum class Target { create_or_replace, in_place };

// Checks `path` (see check_output_path) and says how it will be written.
Target classify(const std::string& path, fs::path& resolved) {
  if (path.empty()) throw Error("empty file name");
  resolved = resolve_links(path);
  struct stat st {};
  if (::stat(resolved.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) throw Error(path + ": is a directory");
    if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) {
      if (::access(resolved.c_str(), W_OK) != 0) throw Error(path + ": " + errno_text(errno));
      return Target::in_place;
    }
    if (!S_ISREG(st.st_mode)) throw Error(path + ": is not a regular file, device or pipe");
    if ((st.st_mode & 0222) == 0)
      throw Error(path + ": is read-only (remove it or make it writable to replace it)");
  } else if (errno != ENOENT) {
    throw Error(path + ": " + errno_text(errno));
  }
  const fs::path dir = folder_of(resolved);
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw Error(path + ": folder '" + dir.string() + "' does not exist");
  if (::access(dir.c_str(), W_OK) != 0)
    throw Error(path + ": folder '" + dir.string() + "' is not writable");
  return Target::create_or_replace;
}

void write_all(int fd, std::string_view bytes, const std::string& path) {
  const char* p = bytes.data();
  std::size_t left = bytes.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) cannot_write(path, errno_text(errno));
    if (n == 0) cannot_write(path, "the device accepts no more data");
    p += n;
    left -= static_cast<std::size_t>(n);
  }
}

void write_in_place(const fs::path& target, const std::string& path, std::string_view bytes) {
  const int fd = ::open(target.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) cannot_write(path, errno_text(errno));
  try {
    write_all(fd, bytes, path);
  } catch (...) {
    ::close(fd);
    throw;
  }
  if (::close(fd) != 0) cannot_write(path, errno_text(errno));
}

}  // namespace

// ---- TemporaryFile ----------------------------------------------------------------------

TemporaryFile::TemporaryFile(const std::string& target, const std::string& shown_as)
    : target_(target), shown_as_(shown_as) {
  if (g_has_registered) throw std::logic_error("rt2: a temporary output file is already open");
  const fs::path t(target);
  path_ = (folder_of(t) / ("." + t.stem().string() + ".tmp" + std::to_string(::getpid()) +
                           t.extension().string()))
              .string();
  if (path_.size() >= sizeof g_registered) cannot_write(shown_as_, "path too long");
  install_handlers_once();
  std::memcpy(g_registered, path_.c_str(), path_.size() + 1);
  g_has_registered = 1;
  ::unlink(path_.c_str());  // left by a killed process that had our PID: ours by its name
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd_ < 0) {
    const int err = errno;
    g_has_registered = 0;
    cannot_write(shown_as_, errno_text(err));
  }
}

TemporaryFile::~TemporaryFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!committed_) ::unlink(path_.c_str());
  g_has_registered = 0;
}

void TemporaryFile::fail(const std::string& why) {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  cannot_write(shown_as_, why);  // the destructor removes the file
}

void TemporaryFile::write(std::string_view bytes) {
  try {
    write_all(fd_, bytes, shown_as_);
  } catch (const Error&) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    throw;
  }
  written_ += bytes.size();
}

void TemporaryFile::commit() {
  // Delayed allocation and network file systems report a full disk only here.
  if (::fsync(fd_) != 0) fail(errno_text(errno));
  struct stat st {};
  if (::fstat(fd_, &st) != 0) fail(errno_text(errno));
  if (static_cast<unsigned long long>(st.st_size) != written_)
    fail("wrote " + std::to_string(written_) + " bytes but the file holds " +
         std::to_string(st.st_size));
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) cannot_write(shown_as_, errno_text(errno));
  if (::rename(path_.c_str(), target_.c_str()) != 0) cannot_write(shown_as_, errno_text(errno));
  committed_ = true;
}

// ---- the API ----------------------------------------------------------------------------

void check_output_path(const std::string& path) {
  fs::path resolved;
  classify(path, resolved);
}

void write_output_file(const std::string& path, std::string_view bytes) {
  fs::path resolved;
  try {
    if (classify(path, resolved) == Target::in_place) return write_in_place(resolved, path, bytes);
  } catch (const Error& e) {
    const std::string what = e.what();
    if (what.rfind("cannot write ", 0) == 0) throw;
    // "PATH: reason" from the checks -> "cannot write PATH: reason"
    throw Error("cannot write " + what);
  }
  TemporaryFile tmp(resolved.string(), path);
  tmp.write(bytes);
  tmp.commit();
}

bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
  const fs::path pa = fs::absolute(a, ec).lexically_normal();
  const fs::path pb = fs::absolute(b, ec).lexically_normal();
  return pa == pb;
}

}  // namespace rt2::io
