// An advisory lock (flock(2)) held for an object's lifetime: released when the object is
// destroyed or the process ends, however it ends (a killed process leaves no stale lock,
// unlike a lock file whose existence is the lock).
#pragma once

#include <filesystem>

namespace stiction::sys {

class FileLock {
 public:
  enum class Mode { shared, exclusive };

  // Locks `path`: a directory on itself, a file created when missing (mode 0644, never
  // through a symbolic link). With `wait`, blocks until the lock is granted; without, returns
  // a FileLock that holds nothing (held() false) when another process holds a conflicting
  // lock. On a file system without locks (ENOLCK, ENOSYS, EOPNOTSUPP) it holds the file
  // unlocked and says held(): callers go on as they did before there were locks.
  // std::system_error when the path cannot be opened or locked otherwise.
  static FileLock acquire(const std::filesystem::path& path, Mode mode, bool wait);

  FileLock() = default;
  FileLock(FileLock&& other) noexcept;
  FileLock& operator=(FileLock&& other) noexcept;
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;
  ~FileLock();

  bool held() const { return fd_ >= 0; }

 private:
  explicit FileLock(int fd) : fd_(fd) {}
  int fd_ = -1;
};

}  // namespace stiction::sys
