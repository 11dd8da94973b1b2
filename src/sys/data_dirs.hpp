// Where the data files (scenes, assets) are, for a relocatable install: the directories are
// tried in this order,
//   1. $STICTION_DATA_DIR, when set;
//   2. <directory of the running executable>/../share/stiction (an installed binary, wherever
//      its prefix was moved to);
//   3. the install prefix configured at build time, <prefix>/share/stiction;
//   4. the source tree (a build tree's binary).
#pragma once

#include <filesystem>
#include <vector>

namespace stiction::sys {

std::vector<std::filesystem::path> data_directories();

// The first data directory holding `relative` (a file or directory), or empty.
std::filesystem::path find_data(const std::filesystem::path& relative);

}  // namespace stiction::sys
