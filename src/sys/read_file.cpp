#include "sys/read_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace stiction::sys {
namespace {

std::string kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

std::string mib(std::uintmax_t bytes) {
  return std::to_string(bytes / (1024 * 1024)) + " MiB";
}

// Closes the descriptor on every way out.
struct Descriptor {
  int fd;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::string read_regular_file(const std::filesystem::path& path, std::uintmax_t max_bytes) {
  struct stat before {};
  if (::stat(path.c_str(), &before) != 0) {
    throw FileRefused(std::string("cannot open it: ") + std::strerror(errno));
  }
  if (!S_ISREG(before.st_mode)) {
    throw FileRefused("it is " + kind_of(before.st_mode) + ", not a regular file");
  }
  // O_NONBLOCK: should the path have become a FIFO since the stat, the open returns at once.
  const Descriptor file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY)};
  if (file.fd < 0) throw FileRefused(std::string("cannot open it: ") + std::strerror(errno));
  struct stat opened {};
  if (::fstat(file.fd, &opened) != 0 || !S_ISREG(opened.st_mode)) {
    throw FileRefused("it is " + kind_of(opened.st_mode) + ", not a regular file");
  }
  const auto size = static_cast<std::uintmax_t>(opened.st_size);
  if (size > max_bytes) {
    throw FileRefused("it is " + std::to_string(size) + " bytes, above the " + mib(max_bytes) +
                      " a file of this kind may have");
  }
  std::string text;
  text.reserve(static_cast<std::size_t>(size));
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(file.fd, buffer, sizeof buffer);
    if (n == 0) break;
    if (n < 0) {
      if (errno == EINTR) continue;
      throw FileRefused(std::string("cannot read it: ") + std::strerror(errno));
    }
    // The file may grow while it is read: the bound holds for what is read, not only for
    // what stat said.
    if (text.size() + static_cast<std::size_t>(n) > max_bytes) {
      throw FileRefused("it grew above the " + mib(max_bytes) + " a file of this kind may have");
    }
    text.append(buffer, static_cast<std::size_t>(n));
  }
  return text;
}

}  // namespace stiction::sys
