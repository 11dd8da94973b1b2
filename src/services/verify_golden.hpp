// A golden set's directory as `stiction verify` may touch it (docs/command_line.md, verify):
// read only as regular files, its golden.json naming only files inside it, and replaced by
// `--update` as one step.
#pragma once

#include <filesystem>

namespace stiction::services {

// Before anything is simulated: golden.json (when present) and every entry of `dir` must be
// regular files (a FIFO or a device would block a read for ever), and every "file" that
// golden.json names must be a plain file name inside `dir` (no "/", "..", absolute path).
// scene::InputError (exit 2) naming golden.json and the entry, or the special file.
void check_golden_set(const std::filesystem::path& dir);

// The new golden set of `--update`, written into a sibling directory
// (PARENT/.NAME.staging-PID) and swapped with the old one by rename at commit(): a failure
// part-way leaves the old set as it was (the stage is removed). Files in the old directory
// that no golden.json names (a README) are carried over.
class GoldenStage {
 public:
  explicit GoldenStage(std::filesystem::path golden_dir);
  ~GoldenStage();  // removes the stage unless committed
  GoldenStage(const GoldenStage&) = delete;
  GoldenStage& operator=(const GoldenStage&) = delete;

  const std::filesystem::path& path() const { return stage_; }
  // Carries over the old directory's files that `named` does not name, then swaps.
  // io::IoError when the swap fails (the old set then stays).
  void commit();

 private:
  std::filesystem::path golden_, stage_;
  bool committed_ = false;
};

}  // namespace stiction::services
