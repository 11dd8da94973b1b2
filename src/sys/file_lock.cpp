#include "sys/file_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>

namespace stiction::sys {

FileLock FileLock::acquire(const std::filesystem::path& path, Mode mode, bool wait) {
  std::error_code ec;
  const bool directory = std::filesystem::is_directory(std::filesystem::symlink_status(path, ec));
  const int fd = directory ? ::open(path.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)
                           : ::open(path.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd < 0) throw std::system_error(errno, std::generic_category(), path.string());
  const int operation = (mode == Mode::shared ? LOCK_SH : LOCK_EX) | (wait ? 0 : LOCK_NB);
  int result;
  do {
    result = ::flock(fd, operation);
  } while (result != 0 && errno == EINTR && wait);
  if (result != 0) {
    const int error = errno;
    // A file system without locks (Lustre mounted without flock, some FUSE systems): the
    // caller goes on unlocked, as it did before there were locks, rather than failing.
    if (error == ENOLCK || error == ENOSYS || error == EOPNOTSUPP) return FileLock(fd);
    ::close(fd);
    if (error == EWOULDBLOCK) return FileLock();
    throw std::system_error(error, std::generic_category(), path.string());
  }
  return FileLock(fd);
}

FileLock::FileLock(FileLock&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }

FileLock& FileLock::operator=(FileLock&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = other.fd_;
    other.fd_ = -1;
  }
  return *this;
}

FileLock::~FileLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the flock
}

}  // namespace stiction::sys
