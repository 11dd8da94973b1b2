// Where the data files (scenes, assets) are, for a relocatable install: the directories are
// tried in this order,
//   1. $STICTION_DATA_DIR, when set;
//   2. <install root>/share/stiction when a host program set the root (the Python module sets
//      the prefix it was installed in, wherever that prefix was moved to);
//   3. <directory of the running executable>/../share/stiction (an installed binary, wherever
//      its prefix was moved to);
//   4. the install prefix configured at build time, <prefix>/share/stiction;
//   5. the source tree (a build tree's binary).
#pragma once

#include <filesystem>
#include <vector>

namespace stiction::sys {

std::vector<std::filesystem::path> data_directories();

// The prefix the running code was installed in, for code that is not the `stiction`
// executable (the Python module); empty when not set. The render plugin is looked for there
// too (services/render_loader.hpp).
void set_install_root(const std::filesystem::path& prefix);
std::filesystem::path install_root();

// The first data directory holding `relative` (a file or directory), or empty.
std::filesystem::path find_data(const std::filesystem::path& relative);

}  // namespace stiction::sys
