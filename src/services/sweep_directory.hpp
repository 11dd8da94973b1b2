// A sweep's directory (docs/sweeps.md): sweep.plan.json, the table (sweep.csv, or one
// sweep.shard-K.csv per shard, resumed after an interruption), the report, and the merge of
// the shards.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "services/sweep.hpp"
#include "sys/file_lock.hpp"

namespace stiction::services {

// Makes `out` this sweep's directory (docs/sweeps.md, "The sweep directory"): the plan it
// already holds must be this one (shards of one sweep share it; the same sweep resumes), a
// directory holding another sweep's plan, or no plan but other files, is refused
// (scene::InputError, exit 2, naming the plan or some files) unless `overwrite`, which
// removes the other sweep's own files (its tables, report and points/) first. Also removes
// what a killed run of this shard left: the temporaries of its table (and, unsharded, of the
// report) and those of its points' directories. A table or `points` that is a link or not a
// regular file / directory is refused.
// The claim holds locks for its lifetime (issue 39: two sweeps started into one --out at the
// same moment both exited 0 with their points mixed): the directory is examined and its plan
// written under an exclusive lock (DIR/.stiction-sweep.claim), so of two sweeps the second
// always sees the first's plan; then an unsharded sweep holds DIR/.stiction-sweep.running
// exclusively, a shard holds it shared and its own DIR/.stiction-sweep.shard-K exclusively.
// A sweep that would run beside another in the directory (the same unsharded sweep twice,
// the same shard twice, an unsharded sweep beside shards, --overwrite of a sweep that runs)
// is refused with io::IoError (exit 1) naming the directory. The shards of one sweep run
// side by side as before. Keep the returned claim until the sweep has written everything.
struct SweepClaim {
  sys::FileLock running, shard;
};
[[nodiscard]] SweepClaim claim_sweep_directory(const SweepPlan& plan,
                                               const std::filesystem::path& out,
                                               const Shard& shard, bool overwrite);

// The table at `path` as far as a previous run of this sweep got: the rows `shard` owns
// whose values are the plan's (with `force_step`, less the points the guard refused before),
// rewritten so that a row cut short by an interruption is dropped. scene::InputError when
// the file has other columns.
SweepTable resume_sweep_table(const SweepPlan& plan, const std::filesystem::path& path,
                              const Shard& shard, bool force_step);

// Writes a whole sweep into `dir`: sweep.plan.json, sweep.csv and the report (sweep.md, and
// sweep.png and sweep.svg when there is something to plot; false when not), into a directory
// claimed as claim_sweep_directory does (another sweep's, or a non-empty one that is no
// sweep's, refused unless `overwrite`).
bool write_sweep(const SweepPlan& plan, const SweepTable& table, const std::filesystem::path& dir,
                 bool overwrite = false);

struct SweepMerge {
  std::size_t shards = 0, points = 0, missing = 0, duplicated = 0;
  std::vector<std::string> problems;  // empty: merged, sweep.csv and the report written
};

// Merges dir's sweep.shard-K.csv into sweep.csv and the report, when every point of
// sweep.plan.json is in exactly one shard. io::IoError for no shard or columns that differ.
SweepMerge merge_sweep_shards(const std::filesystem::path& dir);

}  // namespace stiction::services
