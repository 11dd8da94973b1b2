#include "sys/temporaries.hpp"

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <system_error>

#include <fcntl.h>
#include <unistd.h>

namespace stiction::sys {
namespace {

// A slot is free (0), being filled or emptied (1), or holds a path a handler may unlink (2).
// The handler only reads slots in state 2, whose path is complete and stays put until the
// owner moves the slot away from 2 again.
constexpr int kSlots = 256;
constexpr std::size_t kPathMax = 4096;
struct Slot {
  std::atomic<int> state{0};
  char path[kPathMax];
};
Slot slots[kSlots];  // the one global: a signal handler has nowhere else to look
static_assert(std::atomic<int>::is_always_lock_free);

void track(const std::string& path) {
  if (path.size() >= kPathMax) return;  // cannot be tracked: removed by its owner only
  for (Slot& slot : slots) {
    int expected = 0;
    if (!slot.state.compare_exchange_strong(expected, 1)) continue;
    std::memcpy(slot.path, path.c_str(), path.size() + 1);
    slot.state.store(2);
    return;
  }
}

}  // namespace

Temporary create_temporary(const std::filesystem::path& target) {
  const std::filesystem::path dir = target.has_parent_path() ? target.parent_path() : ".";
  std::random_device seed;
  std::mt19937_64 random((static_cast<std::uint64_t>(seed()) << 32) ^ seed() ^
                         static_cast<std::uint64_t>(::getpid()));
  int error = 0;
  for (int attempt = 0; attempt < 100; ++attempt) {
    char suffix[17];
    std::snprintf(suffix, sizeof suffix, "%016llx", static_cast<unsigned long long>(random()));
    // Appended piecewise: `"." + std::string` trips GCC 12's false -Wrestrict (PR 105329).
    std::string name(1, '.');
    name += target.filename().string();
    name += ".tmp-";
    name += suffix;
    const std::filesystem::path path = dir / name;
    // Mode 0666 rather than mkstemp's 0600: the file gets what the umask allows, like any
    // output the user creates.
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd >= 0) {
      track(path.string());
      return {fd, path};
    }
    error = errno;
    if (error != EEXIST && error != ELOOP) break;
  }
  throw std::system_error(error, std::generic_category(),
                          target.string() + ": cannot create a temporary file");
}

void forget_temporary(const std::filesystem::path& path) {
  const std::string p = path.string();
  for (Slot& slot : slots) {
    if (slot.state.load() != 2 || p != slot.path) continue;
    int expected = 2;
    if (slot.state.compare_exchange_strong(expected, 1)) {
      slot.path[0] = '\0';
      slot.state.store(0);
      return;
    }
  }
}

void remove_registered_temporaries() noexcept {
  for (Slot& slot : slots) {
    if (slot.state.load() == 2) ::unlink(slot.path);
  }
}

}  // namespace stiction::sys
