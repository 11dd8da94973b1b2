#include "sys/data_dirs.hpp"

#include <cstdlib>
#include <system_error>

namespace stiction::sys {
namespace fs = std::filesystem;
namespace {

fs::path& root() {
  static fs::path prefix;
  return prefix;
}

}  // namespace

void set_install_root(const fs::path& prefix) { root() = prefix; }
fs::path install_root() { return root(); }

std::vector<fs::path> data_directories() {
  std::vector<fs::path> dirs;
  if (const char* env = std::getenv("STICTION_DATA_DIR"); env != nullptr && *env != '\0') dirs.emplace_back(env);
  if (!install_root().empty()) dirs.push_back(install_root() / "share" / "stiction");
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec && exe.has_parent_path()) {
    dirs.push_back((exe.parent_path() / ".." / "share" / "stiction").lexically_normal());
  }
  dirs.emplace_back(STICTION_INSTALL_DATA_DIR);
  dirs.emplace_back(STICTION_SOURCE_DATA_DIR);
  return dirs;
}

fs::path find_data(const fs::path& relative) {
  for (const fs::path& dir : data_directories()) {
    std::error_code ec;
    if (fs::exists(dir / relative, ec)) return dir / relative;
  }
  return {};
}

}  // namespace stiction::sys
