// Temporary files for atomic writes (DESIGN section 4), created safely in the target's own
// directory and removable from a signal handler.
//
// Each temporary is "DIR/.NAME.tmp-" + 16 random hex digits, opened with
// O_CREAT | O_EXCL | O_NOFOLLOW: a name planted in advance (a file or a symlink to somewhere
// else, in a shared output directory) makes the open fail and another name is drawn, so the
// program never writes through a link. While it exists the path is registered in a fixed
// table that remove_registered_temporaries() walks with unlink() only, which is safe inside
// a signal handler (sys/interrupt.hpp uses it on a second Ctrl-C).
#pragma once

#include <filesystem>

namespace stiction::sys {

struct Temporary {
  int fd = -1;  // open for writing, O_CLOEXEC
  std::filesystem::path path;
};

// std::system_error when no temporary can be created (the directory is missing or
// not writable).
Temporary create_temporary(const std::filesystem::path& target);

// The temporary was renamed or removed: stop tracking it.
void forget_temporary(const std::filesystem::path& path);

// Unlinks every registered temporary. Async-signal-safe.
void remove_registered_temporaries() noexcept;

}  // namespace stiction::sys
