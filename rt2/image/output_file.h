// rt2/image/output_file.h — files that appear whole or not at all.
//
// Every file rt2 writes (images, statistics) goes through here. The bytes go to a temporary
// file beside the target, ".NAME.tmpPID.EXT"; each write is checked, the data is flushed to
// the disk (fsync), the file's size is checked against what was written, the close is
// checked, and only then is it renamed over the target. A failure at any step removes the
// temporary file and throws rt2::Error "cannot write PATH: reason" (a full disk, a quota,
// an I/O error). While the temporary file exists its path is registered for removal: if
// the process is stopped by SIGINT, SIGTERM, SIGHUP or SIGQUIT, a handler unlinks it and
// re-raises the signal; if a library calls exit(), an atexit handler does.
#pragma once

#include <string>
#include <string_view>

namespace rt2::io {

// What a target may be:
// - a new name, or an existing regular file: replaced atomically. An existing file with no
//   write permission bit is refused ("is read-only"), for root as for anyone: its owner
//   protected it, and a rename would silently replace it.
// - a symbolic link: written through. The file the link resolves to is replaced; the link
//   itself stays (a dangling link creates its target).
// - a character device or a FIFO (/dev/null, /dev/stdout, a named pipe): written in place,
//   every write and the close checked (`/dev/full` fails with "No space left on device").
// - an empty path, a directory, a missing folder, a folder without write permission, or
//   another kind of file: refused by check_output_path, before any work is done.
// Throws rt2::Error ("PATH: reason", one line) unless `path` can be written as above.
void check_output_path(const std::string& path);

// Writes `bytes` to `path` as described above. Throws rt2::Error "cannot write PATH:
// reason" on any failure, leaving the target as it was and no temporary file behind.
void write_output_file(const std::string& path, std::string_view bytes);

// True when `a` and `b` name the same file: the same inode when both exist
// (std::filesystem::equivalent, so links and "./x" are seen through), otherwise the same
// absolute, normalised path.
bool same_file(const std::string& a, const std::string& b);

// The temporary file of one write, registered for removal on a signal or exit() while it
// exists (see above). Only one can be registered at a time (rt2 writes one file at a
// time); constructing a second while one is alive is a programming error (std::logic_error).
class TemporaryFile {
 public:
  // Creates ".NAME.tmpPID.EXT" (mode 0666 minus the umask) beside `target` (a path with no
  // symbolic link left to follow), which commit() will replace. Errors name the file as
  // `shown_as` (the path the user gave): rt2::Error "cannot write SHOWN_AS: reason".
  TemporaryFile(const std::string& target, const std::string& shown_as);
  ~TemporaryFile();  // removes the file unless commit() succeeded
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;

  const std::string& path() const { return path_; }
  int fd() const { return fd_; }
  // Writes all of `bytes` at the current position; throws on a short or failed write.
  void write(std::string_view bytes);
  // fsync, size check against everything written, close, rename onto `target`.
  void commit();

 private:
  [[noreturn]] void fail(const std::string& why);
  std::string path_, target_, shown_as_;
  int fd_ = -1;
  unsigned long long written_ = 0;
  bool committed_ = false;
};

}  // namespace rt2::io
