// A run's output directory as the program's own (DESIGN section 4, docs/limits.md "The
// output directory"):
//
// - it is locked for the run's lifetime (flock on the directory itself; a second run into it
//   fails at once instead of mixing its files with the first run's);
// - a manifest, DIR/.stiction-output (written atomically: one relative path a line), names
//   the files the last run wrote there; only those are ever deleted or replaced. A directory
//   written by an older stiction counts as one with a manifest when its summary.json lists
//   `files`. A NON-EMPTY directory without a manifest is refused (exit 2, naming some of its
//   files) unless `overwrite`: then the run may write into it, replacing files of the names
//   it writes, and deleting nothing else. A directory with a manifest that holds a file of a
//   name a run writes (plots/*.png, trajectory.csv, ...) that the manifest does not list is
//   refused the same way. "/" and the home directory are refused always;
// - never through a symlink: `plots` or `frames` inside it that is a link (or not a
//   directory) is refused with exit 2; a link under a file's name is replaced, never
//   written through;
// - staged: the run writes into DIR/.stiction-staging-PID/ and commit() moves its files into
//   place at the end (rename), then removes the earlier run's files that were not replaced
//   and writes the manifest. Until then the previous run's files stay as they were; a run
//   that fails (exception, exit 1) leaves them intact and its staging directory is removed.
//   A staging directory left by a killed run is removed by the next run (under the lock).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace stiction::services {

struct OutputOptions {
  bool overwrite = false;  // --overwrite: write into a non-empty directory without a manifest
};

class OutputDirectory {
 public:
  // Checks ownership (scene::InputError, exit 2), creates the directory, takes the lock,
  // creates the staging directory (io::IoError, exit 1). Touches none of the earlier files.
  explicit OutputDirectory(std::filesystem::path dir, const OutputOptions& options = {});
  ~OutputDirectory();  // removes the staging directory unless committed; releases the lock
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

  // Where files are written now: the staging directory.
  const std::filesystem::path& path() const { return staging_; }
  std::filesystem::path operator/(const std::filesystem::path& relative) const {
    return staging_ / relative;
  }
  // The output directory itself, and where a file will be after commit().
  const std::filesystem::path& directory() const { return dir_; }
  std::filesystem::path final_path(const std::filesystem::path& staged_or_relative) const;

  // Records a file written by this run (a staged path, or relative to the directory).
  void wrote(const std::filesystem::path& file);
  // The recorded files, relative to the directory, in the order written (no duplicates).
  nlohmann::ordered_json files() const;

  // Moves every recorded file into the directory, removes the earlier run's files that this
  // run did not replace, writes the manifest and removes the staging directory. io::IoError
  // when a file cannot be moved (the earlier files not yet replaced stay, and the manifest
  // names both runs' files).
  void commit();

 private:
  void check_ownership(const OutputOptions& options);
  void write_manifest(const std::vector<std::string>& files) const;
  std::filesystem::path dir_, staging_;
  int lock_fd_ = -1;
  bool committed_ = false;
  std::vector<std::string> earlier_;  // the manifest's files (the earlier run's)
  std::vector<std::string> files_;
};

// The name of the manifest inside an output directory.
inline constexpr const char* kOutputManifest = ".stiction-output";

}  // namespace stiction::services
