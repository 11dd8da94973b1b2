// Output files that are either complete or absent (DESIGN section 4): the content goes to a
// hidden temporary file in the target's directory (sys/temporaries.hpp: O_EXCL, O_NOFOLLOW) and is
// renamed over the target only by commit(). A crash or an exception before commit() leaves
// the previous file (if any) untouched and no file with the target's name half-written.
// rename() within one directory is atomic on POSIX; no fsync: this guards against partial
// files from our own failures, not against power loss.
#pragma once

#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace stiction::io {

// Any failure to write output (exit code 1).
class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path target);
  ~AtomicFile();  // removes the temporary file unless committed
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  void write(std::string_view data);
  // Flushes, closes and renames onto the target. IoError on any failure.
  void commit();

  const std::filesystem::path& target() const { return target_; }
  const std::filesystem::path& temporary() const { return temporary_; }

 private:
  std::filesystem::path target_;
  std::filesystem::path temporary_;
  std::FILE* file_ = nullptr;
  bool committed_ = false;
};

// The whole content at once.
void write_file_atomically(const std::filesystem::path& target, std::string_view content);

}  // namespace stiction::io
