#include "services/output_dir.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <set>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include "io/atomic_file.hpp"
#include "scene/toml_reader.hpp"
#include "services/owned_files.hpp"

namespace stiction::services {
namespace fs = std::filesystem;
namespace {

constexpr const char* kStagingPrefix = ".stiction-staging-";

bool is_staging(const std::string& name) { return name.rfind(kStagingPrefix, 0) == 0; }

bool run_output(const std::string& dir, const std::string& name) {
  if (dir.empty()) {
    return name == "trajectory.csv" || name == "summary.json" || name == "video.mp4" ||
           name == "video.partial.mp4";
  }
  if (dir == "frames") return is_frame_name(name);
  if (dir == "plots") return is_plot_name(name);
  return false;
}

// "/" or the home directory: never an output directory, whatever the options.
void refuse_system_directory(const fs::path& dir) {
  std::error_code ec;
  const fs::path where = fs::weakly_canonical(fs::absolute(dir, ec), ec);
  if (ec) return;
  const char* home = std::getenv("HOME");
  const bool root = where == where.root_path();
  const bool is_home = home != nullptr && *home != '\0' && where == fs::weakly_canonical(home, ec);
  if (root || is_home) {
    throw scene::InputError("error: --out " + dir.string() + ": refusing to write into " +
                            (root ? std::string("the root directory") : "the home directory") +
                            "; choose a directory of its own");
  }
}

// Names the entries of `found` (at most 5) for a refusal.
std::string name_some(const std::vector<std::string>& found) {
  std::string text;
  for (std::size_t i = 0; i < found.size() && i < 5; ++i) text += (i ? ", " : "") + found[i];
  if (found.size() > 5) text += " and " + std::to_string(found.size() - 5) + " more";
  return text;
}

// A subdirectory the run writes into (plots, frames) must be a real directory or absent.
void refuse_linked_subdirectory(const fs::path& dir, const char* sub) {
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(dir / sub, ec);
  if (ec || !fs::exists(st)) return;
  if (fs::is_symlink(st)) {
    throw scene::InputError("error: " + (dir / sub).string() +
                            " is a symbolic link; stiction never writes through a link in its "
                            "output directory: remove it or choose another --out");
  }
  if (!fs::is_directory(st)) {
    throw scene::InputError("error: " + (dir / sub).string() +
                            " is not a directory; stiction writes its " + sub +
                            " there: remove it or choose another --out");
  }
}

}  // namespace

OutputDirectory::OutputDirectory(fs::path dir, const OutputOptions& options)
    : dir_(std::move(dir)) {
  refuse_system_directory(dir_);
  std::error_code ec;
  const fs::file_status st = fs::status(dir_, ec);
  if (fs::exists(st) && !fs::is_directory(st)) {
    throw scene::InputError("error: --out " + dir_.string() + ": exists and is not a directory");
  }
  fs::create_directories(dir_, ec);
  if (ec) throw io::IoError(dir_.string() + ": cannot create the output directory: " + ec.message());
  // The lock is on the directory itself: no lock file to leave behind, and nothing a
  // planted symlink could redirect.
  lock_fd_ = ::open(dir_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (lock_fd_ < 0) {
    throw io::IoError(dir_.string() + ": cannot open the output directory: " + std::strerror(errno));
  }
  if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    ::close(lock_fd_);
    lock_fd_ = -1;
    if (error == EWOULDBLOCK) {
      throw io::IoError(dir_.string() + ": another stiction run is writing into this directory "
                        "(it holds its lock); wait for it or choose another --out");
    }
    throw io::IoError(dir_.string() + ": cannot lock the output directory: " + std::strerror(error));
  }
  try {
    check_ownership(options);
    // What a killed run left: its staging directory and temporaries (ours by their names).
    for (const auto& entry : fs::directory_iterator(dir_, ec)) {
      if (is_staging(entry.path().filename().string())) fs::remove_all(entry.path(), ec);
    }
    for (const char* sub : {"", "plots", "frames"}) remove_temporaries(dir_ / sub);
    staging_ = dir_ / (kStagingPrefix + std::to_string(::getpid()));
    fs::remove_all(staging_, ec);
    if (!fs::create_directory(staging_, ec) || ec) {
      throw io::IoError(dir_.string() + ": cannot write into the output directory: " +
                        (ec ? ec.message() : std::string("staging directory exists")));
    }
  } catch (...) {
    ::close(lock_fd_);
    lock_fd_ = -1;
    throw;
  }
}

OutputDirectory::~OutputDirectory() {
  if (!committed_ && !staging_.empty()) {
    std::error_code ec;
    fs::remove_all(staging_, ec);  // a failed run: the earlier files stay as they were
  }
  if (lock_fd_ >= 0) ::close(lock_fd_);  // releases the flock
}

void OutputDirectory::check_ownership(const OutputOptions& options) {
  refuse_linked_subdirectory(dir_, "plots");
  refuse_linked_subdirectory(dir_, "frames");
  const std::optional<std::vector<std::string>> manifest = read_output_manifest(dir_);
  std::vector<std::string> found;
  if (!manifest) {
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir_, ec)) {
      const std::string name = entry.path().filename().string();
      if (!is_staging(name) && !is_temporary_name(name)) found.push_back(name);
    }
    std::sort(found.begin(), found.end());
    if (!found.empty() && !options.overwrite) {
      throw scene::InputError(
          "error: --out " + dir_.string() + ": the directory is not empty and holds no " +
          kOutputManifest + " (it is not a stiction output directory): " + name_some(found) +
          "; choose another --out, or give --overwrite to write into it anyway (files of the "
          "names stiction writes are replaced, nothing else is deleted)");
    }
    return;
  }
  earlier_ = *manifest;
  const std::set<std::string> listed(earlier_.begin(), earlier_.end());
  for (const char* sub : {"", "plots", "frames"}) {
    std::error_code ec;
    if (!fs::is_directory(fs::symlink_status(dir_ / sub, ec))) continue;
    for (const auto& entry : fs::directory_iterator(dir_ / sub, ec)) {
      const std::string name = entry.path().filename().string();
      const std::string relative = *sub ? std::string(sub) + "/" + name : name;
      if (run_output(sub, name) && !listed.count(relative)) found.push_back(relative);
    }
  }
  std::sort(found.begin(), found.end());
  if (!found.empty() && !options.overwrite) {
    throw scene::InputError("error: --out " + dir_.string() + ": " + name_some(found) +
                            " not written by stiction (not in " + kOutputManifest +
                            "); move it away, choose another --out, or give --overwrite to "
                            "replace files of the names stiction writes");
  }
}

fs::path OutputDirectory::final_path(const fs::path& file) const {
  const fs::path relative = file.lexically_relative(staging_);
  if (!relative.empty() && *relative.begin() != "..") return dir_ / relative;
  return file.is_relative() ? dir_ / file : file;
}

void OutputDirectory::wrote(const fs::path& file) {
  // Callers pass paths built as out / name (the staging directory); a relative one is kept.
  fs::path relative = file.lexically_relative(staging_);
  if (relative.empty() || *relative.begin() == "..") relative = file;
  const std::string name = relative.generic_string();
  if (std::find(files_.begin(), files_.end(), name) == files_.end()) files_.push_back(name);
}

nlohmann::ordered_json OutputDirectory::files() const {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const std::string& f : files_) list.push_back(f);
  return list;
}

void OutputDirectory::write_manifest(const std::vector<std::string>& files) const {
  write_output_manifest(dir_, files);
}

void OutputDirectory::commit() {
  // First the manifest names both runs' files: whatever stops the swap, every file of ours
  // in the directory is named by it.
  std::vector<std::string> both = earlier_;
  for (const std::string& f : files_) {
    if (std::find(both.begin(), both.end(), f) == both.end()) both.push_back(f);
  }
  write_manifest(both);
  for (const std::string& f : files_) {
    const fs::path target = dir_ / f;
    make_real_directories(dir_, fs::path(f).parent_path());
    if (::rename((staging_ / f).c_str(), target.c_str()) != 0) {
      throw io::IoError(target.string() + ": cannot move into place: " + std::strerror(errno));
    }
  }
  const std::set<std::string> kept(files_.begin(), files_.end());
  for (const std::string& f : earlier_) {
    if (!kept.count(f)) remove_owned_file(dir_ / f);
  }
  for (const char* sub : {"plots", "frames"}) {
    std::error_code ec;
    if (fs::is_directory(fs::symlink_status(dir_ / sub, ec))) fs::remove(dir_ / sub, ec);  // if empty
  }
  write_manifest(files_);
  std::error_code ec;
  fs::remove_all(staging_, ec);
  committed_ = true;
}

}  // namespace stiction::services
