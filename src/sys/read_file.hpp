// Reading a file the user named, safely (issue 39): only a regular file (a FIFO would block
// for ever, /dev/zero would fill the memory, a directory is no document), within a size
// bound, opened without blocking and checked again on the open descriptor, so that a file
// swapped for a FIFO between the check and the open is refused too.
#pragma once

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace stiction::sys {

// Why a file was not read, as a clause ("it is a FIFO (named pipe), not a regular file",
// "cannot open it: No such file or directory"); the caller names the file and the key.
struct FileRefused : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Scene files, URDF files and golden manifests are text a person writes or a tool
// generates: 64 MiB is far above any real one (a 5000-joint URDF chain is about 2 MB).
inline constexpr std::uintmax_t kMaxInputFileBytes = 64u << 20;

// The whole content of `path`; throws FileRefused when it is not a regular file, is larger
// than `max_bytes`, or cannot be opened or read.
std::string read_regular_file(const std::filesystem::path& path,
                              std::uintmax_t max_bytes = kMaxInputFileBytes);

}  // namespace stiction::sys
