#include "services/verify_golden.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <set>
#include <string>

#include <fcntl.h>
#include <stdio.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "io/atomic_file.hpp"
#include "scene/toml_reader.hpp"
#include "services/owned_files.hpp"

namespace stiction::services {
namespace fs = std::filesystem;
namespace {

// The names golden.json lists under frames and figures (unchecked).
std::vector<std::string> named_files(const nlohmann::json& manifest) {
  std::vector<std::string> names;
  for (const char* list : {"frames", "figures"}) {
    if (!manifest.is_object() || !manifest.contains(list) || !manifest[list].is_array()) continue;
    for (const auto& entry : manifest[list]) {
      if (entry.is_object() && entry.contains("file") && entry["file"].is_string())
        names.push_back(entry["file"].get<std::string>());
    }
  }
  return names;
}

// One plain name: no directory part, nothing that leaves the directory.
bool plain_name(const std::string& name) {
  const fs::path p(name);
  return is_inside(p) && !p.has_parent_path() && name.find('\\') == std::string::npos;
}

// ".NAME." for the stage and the old set beside `golden` (appended: GCC 12's -Wrestrict
// misfires on "." + name + ".").
std::string sibling_prefix(const fs::path& golden) {
  std::string prefix(1, '.');
  prefix.append(golden.filename().string());
  prefix.push_back('.');
  return prefix;
}

// rename(2) of two directories into each other's place in one step where the file system
// can (renameat2 RENAME_EXCHANGE); false when it cannot.
bool exchange(const fs::path& a, const fs::path& b) {
#ifdef RENAME_EXCHANGE
  return ::renameat2(AT_FDCWD, a.c_str(), AT_FDCWD, b.c_str(), RENAME_EXCHANGE) == 0;
#else
  (void)a;
  (void)b;
  return false;
#endif
}

}  // namespace

void check_golden_set(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(fs::status(dir, ec))) return;
  const fs::path inside = fs::canonical(dir, ec);
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const fs::file_status st = entry.status(ec);
    if (!fs::is_regular_file(st) && !fs::is_directory(st)) {
      throw scene::InputError("error: " + entry.path().string() +
                              ": not a regular file (a FIFO, a device, a socket or a broken link) in a "
                              "golden set; only regular files are read: remove it");
    }
    // A link may point within the set, never out of it: a golden set from a pull request
    // must not have `verify` read, compare or quote (in stderr, junit.xml, report.md) a file
    // elsewhere on the machine.
    if (entry.is_symlink(ec)) {
      const fs::path target = fs::canonical(entry.path(), ec);
      const auto [end, _] = std::mismatch(inside.begin(), inside.end(), target.begin(), target.end());
      if (ec || end != inside.end()) {
        throw scene::InputError("error: " + entry.path().string() +
                                ": a link that leaves the golden set; only files inside " +
                                dir.string() + " are read: replace it by the file itself");
      }
    }
  }
  const fs::path manifest_path = dir / "golden.json";
  if (!regular_file_or_absent(manifest_path)) return;
  std::ifstream in(manifest_path);
  const nlohmann::json manifest = nlohmann::json::parse(in, nullptr, false);
  for (const std::string& name : named_files(manifest)) {
    if (!plain_name(name)) {
      throw scene::InputError("error: " + manifest_path.string() + ": \"file\": \"" + name +
                              "\": a golden set's files are plain names inside its directory");
    }
  }
}

GoldenStage::GoldenStage(fs::path golden_dir) : golden_(std::move(golden_dir)) {
  const fs::path parent = golden_.parent_path().empty() ? fs::path(".") : golden_.parent_path();
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) throw io::IoError(parent.string() + ": cannot create the directory: " + ec.message());
  // Leftovers of a killed update of this set go first (ours by their name).
  const std::string prefix = sibling_prefix(golden_);
  for (const auto& entry : fs::directory_iterator(parent, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) == 0 &&
        (name.find(".staging-") != std::string::npos || name.find(".old-") != std::string::npos)) {
      fs::remove_all(entry.path(), ec);
    }
  }
  stage_ = parent / (prefix + "staging-" + std::to_string(::getpid()));
  fs::remove_all(stage_, ec);
  if (!fs::create_directory(stage_, ec) || ec) {
    throw io::IoError(stage_.string() + ": cannot create the golden set's stage: " + ec.message());
  }
}

GoldenStage::~GoldenStage() {
  if (committed_) return;
  std::error_code ec;
  fs::remove_all(stage_, ec);
}

void GoldenStage::commit() {
  std::error_code ec;
  const bool had_old = fs::is_directory(fs::symlink_status(golden_, ec));
  if (had_old) {
    // The user's files beside the set (a README) go along; the old set's own files do not.
    std::set<std::string> owned{"golden.json"};
    const fs::path manifest_path = golden_ / "golden.json";
    if (regular_file_or_absent(manifest_path)) {
      std::ifstream in(manifest_path);
      for (const std::string& n : named_files(nlohmann::json::parse(in, nullptr, false)))
        owned.insert(n);
    }
    for (const auto& entry : fs::directory_iterator(golden_, ec)) {
      const std::string name = entry.path().filename().string();
      if (owned.count(name) || fs::exists(fs::symlink_status(stage_ / name, ec))) continue;
      if (fs::is_regular_file(fs::symlink_status(entry.path(), ec))) {
        fs::copy_file(entry.path(), stage_ / name, ec);
      } else {
        fs::copy(entry.path(), stage_ / name, fs::copy_options::recursive | fs::copy_options::copy_symlinks, ec);
      }
      if (ec) throw io::IoError(entry.path().string() + ": cannot carry over: " + ec.message());
    }
  }
  if (!had_old) {
    if (::rename(stage_.c_str(), golden_.c_str()) != 0)
      throw io::IoError(golden_.string() + ": cannot move the new golden set into place: " +
                        std::strerror(errno));
    committed_ = true;
    return;
  }
  if (exchange(stage_, golden_)) {
    committed_ = true;
    fs::remove_all(stage_, ec);  // now the old set
    return;
  }
  // No exchange on this file system: two renames, the old set kept aside until the new one
  // is in place.
  const fs::path old =
      golden_.parent_path() / (sibling_prefix(golden_) + "old-" + std::to_string(::getpid()));
  fs::remove_all(old, ec);
  if (::rename(golden_.c_str(), old.c_str()) != 0)
    throw io::IoError(golden_.string() + ": cannot replace the golden set: " + std::strerror(errno));
  if (::rename(stage_.c_str(), golden_.c_str()) != 0) {
    const int error = errno;
    ::rename(old.c_str(), golden_.c_str());
    throw io::IoError(golden_.string() + ": cannot move the new golden set into place: " +
                      std::strerror(error));
  }
  committed_ = true;
  fs::remove_all(old, ec);
}

}  // namespace stiction::services
