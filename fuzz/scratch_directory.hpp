// A directory of this process for the files a fuzz input carries (its URDF): created on
// first use under the system's temporary directory, removed when the process exits
// normally. Inputs never name it: they reach their files relative to the scene.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace stiction::fuzz {

class ScratchDirectory {
 public:
  ScratchDirectory()
      : path_(std::filesystem::temp_directory_path() /
              ("stiction-fuzz-" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(path_);
  }
  ~ScratchDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

inline const std::filesystem::path& scratch_directory() {
  static const ScratchDirectory directory;
  return directory.path();
}

}  // namespace stiction::fuzz
