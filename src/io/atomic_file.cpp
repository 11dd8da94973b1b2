#include "io/atomic_file.hpp"

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <random>
#include <cstring>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

namespace stiction::io {
namespace fs = std::filesystem;

namespace {
std::string reason() { return std::strerror(errno); }
}  // namespace

AtomicFile::AtomicFile(fs::path target) : target_(std::move(target)) {
  const fs::path dir = target_.has_parent_path() ? target_.parent_path() : fs::path(".");
  // open(O_EXCL) with mode 0666 rather than mkstemp: the file gets the permissions the
  // umask allows, like any file the user creates, without touching the process umask.
  std::random_device seed;
  std::mt19937_64 random(seed() ^ static_cast<std::uint64_t>(::getpid()));
  int fd = -1;
  for (int attempt = 0; attempt < 100 && fd < 0; ++attempt) {
    char suffix[17];
    std::snprintf(suffix, sizeof suffix, "%016llx", static_cast<unsigned long long>(random()));
    // Appended piecewise: `"." + std::string` trips GCC 12's false -Wrestrict (PR 105329).
    std::string name(1, '.');
    name += target_.filename().string();
    name += ".tmp-";
    name += suffix;
    temporary_ = dir / name;
    fd = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno != EEXIST) break;
  }
  if (fd < 0) throw IoError(target_.string() + ": cannot create a temporary file: " + reason());
  file_ = ::fdopen(fd, "wb");
  if (file_ == nullptr) {
    const std::string why = reason();
    ::close(fd);
    ::unlink(temporary_.c_str());
    throw IoError(target_.string() + ": cannot open a temporary file: " + why);
  }
}

AtomicFile::~AtomicFile() {
  if (file_ != nullptr) std::fclose(file_);
  if (!committed_) ::unlink(temporary_.c_str());
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
