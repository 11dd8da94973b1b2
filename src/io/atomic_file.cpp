#include "io/atomic_file.hpp"

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <system_error>
#include <cstring>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

#include "sys/temporaries.hpp"

namespace stiction::io {
namespace fs = std::filesystem;

namespace {
std::string reason() { return std::strerror(errno); }
}  // namespace

AtomicFile::AtomicFile(fs::path target) : target_(std::move(target)) {
  int fd = -1;
  try {
    sys::Temporary temporary = sys::create_temporary(target_);
    fd = temporary.fd;
    temporary_ = std::move(temporary.path);
  } catch (const std::system_error& e) {
    throw IoError(target_.string() + ": cannot create a temporary file: " + e.code().message());
  }
  file_ = ::fdopen(fd, "wb");
  if (file_ == nullptr) {
    const std::string why = reason();
    ::close(fd);
    ::unlink(temporary_.c_str());
    sys::forget_temporary(temporary_);
    throw IoError(target_.string() + ": cannot open a temporary file: " + why);
  }
}

AtomicFile::~AtomicFile() {
  if (file_ != nullptr) std::fclose(file_);
  if (!committed_) ::unlink(temporary_.c_str());
  sys::forget_temporary(temporary_);
}

void AtomicFile::write(std::string_view data) {
  if (file_ == nullptr) throw IoError(target_.string() + ": write after commit");
  if (std::fwrite(data.data(), 1, data.size(), file_) != data.size()) {
    throw IoError(target_.string() + ": write failed: " + reason());
  }
}

void AtomicFile::commit() {
  if (file_ == nullptr) throw IoError(target_.string() + ": committed twice");
  const bool flushed = std::fflush(file_) == 0 && !std::ferror(file_);
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!flushed || !closed) throw IoError(target_.string() + ": write failed: " + reason());
  if (::rename(temporary_.c_str(), target_.c_str()) != 0) {
    throw IoError(target_.string() + ": cannot rename the temporary file: " + reason());
  }
  committed_ = true;
}

void write_file_atomically(const fs::path& target, std::string_view content) {
  AtomicFile file(target);
  file.write(content);
  file.commit();
}

}  // namespace stiction::io
