// A run's output directory as a transaction (DESIGN section 4): the run owns its --out for
// its lifetime through an advisory lock (flock on the directory itself; a second run into the
// same directory fails at once with a clear message instead of mixing its files with the
// first run's), removes what an earlier run wrote there before writing anything, and records
// every file it writes, for `files` in summary.json.
//
// What counts as an earlier run's output: the files its summary.json listed, plus the names
// a run writes (trajectory.csv, summary.json, video.mp4, video.partial.mp4, plots/*.png|svg|
// pdf, frames/NNNNNN.png) and temporaries left by a killed run (".NAME.tmp-*", "NAME.tmp.*").
// Nothing else is touched: a user's own files in the directory stay. Removal never follows a
// symlink (a planted link is removed, never its target).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace stiction::services {

class OutputDirectory {
 public:
  // Creates the directory (and parents), takes the lock, removes the earlier outputs.
  // io::IoError when the directory cannot be created or another run holds it.
  explicit OutputDirectory(std::filesystem::path dir);
  ~OutputDirectory();  // releases the lock
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

  const std::filesystem::path& path() const { return dir_; }
  std::filesystem::path operator/(const std::filesystem::path& relative) const { return dir_ / relative; }

  // Records a file written by this run (absolute, or relative to the directory).
  void wrote(const std::filesystem::path& file);
  // The recorded files, relative to the directory, in the order written (no duplicates).
  nlohmann::ordered_json files() const;

 private:
  void remove_earlier_outputs();
  std::filesystem::path dir_;
  int lock_fd_ = -1;
  std::vector<std::string> files_;
};

}  // namespace stiction::services
