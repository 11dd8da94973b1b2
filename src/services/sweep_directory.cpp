#include "services/sweep_directory.hpp"

#include <algorithm>
#include <optional>
#include <fstream>
#include <sstream>
#include <system_error>

#include "io/atomic_file.hpp"
#include "scene/toml_reader.hpp"
#include "services/owned_files.hpp"

namespace stiction::services {
namespace fs = std::filesystem;
namespace {

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw io::IoError(path.string() + ": cannot read");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

}  // namespace

namespace {

bool is_sweep_file(const std::string& name) {
  return name == "sweep.csv" || name == "sweep.md" || name == "sweep.png" || name == "sweep.svg" ||
         name == "sweep.plan.json" ||
         (name.rfind("sweep.shard-", 0) == 0 && name.size() > 16 && name.ends_with(".csv"));
}

std::string table_name(const Shard& shard) {
  return shard.sharded() ? "sweep.shard-" + std::to_string(shard.index) + ".csv" : "sweep.csv";
}

// NNNNNN of points/NNNNNN, or nullopt.
std::optional<std::size_t> point_index(const std::string& name) {
  if (name.size() != 6 || !std::all_of(name.begin(), name.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return std::nullopt;
  return static_cast<std::size_t>(std::stoul(name));
}

// The sweep's locks (claim_sweep_directory): hidden files that stay, empty, in the directory;
// a lock is released when its process ends, however it ends.
constexpr const char* kLockPrefix = ".stiction-sweep.";
constexpr const char* kClaimLock = ".stiction-sweep.claim";
constexpr const char* kRunningLock = ".stiction-sweep.running";

std::string shard_lock_name(const Shard& shard) {
  return kLockPrefix + ("shard-" + std::to_string(shard.index));
}

sys::FileLock lock(const fs::path& path, sys::FileLock::Mode mode, bool wait) {
  try {
    return sys::FileLock::acquire(path, mode, wait);
  } catch (const std::system_error& e) {
    throw io::IoError(path.string() + ": cannot lock the sweep directory: " + e.code().message());
  }
}

void refuse_special(const fs::path& path, bool directory) {
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(path, ec);
  if (!fs::exists(st)) return;
  if (directory ? !fs::is_directory(st) : !fs::is_regular_file(st)) {
    throw scene::InputError("error: " + path.string() + ": " +
                            (fs::is_symlink(st) ? "a symbolic link" : "not a regular " +
                             std::string(directory ? "directory" : "file")) +
                            "; a sweep never writes through it: remove it or use another --out");
  }
}

// The other sweep's own files: its tables, plan, report, and its points' outputs.
void remove_sweep_files(const fs::path& out) {
  std::error_code ec;
  std::vector<fs::path> doomed;
  for (const auto& entry : fs::directory_iterator(out, ec)) {
    if (is_sweep_file(entry.path().filename().string())) doomed.push_back(entry.path());
  }
  for (const fs::path& p : doomed) remove_owned_file(p);
  if (!fs::is_directory(fs::symlink_status(out / "points", ec))) return;
  for (const auto& entry : fs::directory_iterator(out / "points", ec)) {
    if (!point_index(entry.path().filename().string()) ||
        !fs::is_directory(fs::symlink_status(entry.path(), ec)))
      continue;
    for (const char* name : {"summary.json", "trajectory.csv"}) remove_owned_file(entry.path() / name);
    remove_temporaries(entry.path());
    fs::remove(entry.path(), ec);  // if now empty
  }
  fs::remove(out / "points", ec);  // if now empty
}

}  // namespace

SweepClaim claim_sweep_directory(const SweepPlan& plan, const fs::path& out, const Shard& shard,
                                 bool overwrite) {
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw io::IoError(out.string() + ": cannot create the sweep directory: " + ec.message());
  const fs::path path = out / "sweep.plan.json";
  const std::string text = plan.to_json();
  for (const char* name : {kClaimLock, kRunningLock}) refuse_special(out / name, false);
  if (shard.sharded()) refuse_special(out / shard_lock_name(shard), false);
  // Held while the directory is examined and the plan written: two sweeps never both find
  // it free.
  const sys::FileLock claiming = lock(out / kClaimLock, sys::FileLock::Mode::exclusive, true);
  SweepClaim claim;
  const auto running_elsewhere = [&](const std::string& what) {
    return io::IoError(out.string() + ": " + what +
                       " is writing into this directory (it holds " +
                       (out / kRunningLock).string() +
                       "); wait for it to end or choose another --out");
  };
  refuse_special(path, false);
  refuse_special(out / table_name(shard), false);
  refuse_special(out / "points", true);
  if (fs::exists(fs::symlink_status(path, ec))) {
    if (read_text(path) != text) {
      if (!overwrite) {
        throw scene::InputError("error: " + path.string() +
                                " describes another sweep (other scene or scene content, keys, "
                                "values, records, --set, --dt, --duration, --integrator or "
                                "--tolerance); use another --out, or --overwrite to replace it");
      }
      // Never the files of a sweep that is running.
      if (!lock(out / kRunningLock, sys::FileLock::Mode::exclusive, false).held())
        throw running_elsewhere("another stiction sweep");
      remove_sweep_files(out);
    }
  } else {
    std::vector<std::string> found;
    for (const auto& entry : fs::directory_iterator(out, ec)) {
      const std::string name = entry.path().filename().string();
      if (!is_temporary_name(name) && !name.starts_with(kLockPrefix)) found.push_back(name);
    }
    std::sort(found.begin(), found.end());
    if (!found.empty() && !overwrite) {
      std::string names;
      for (std::size_t i = 0; i < found.size() && i < 5; ++i) names += (i ? ", " : "") + found[i];
      if (found.size() > 5) names += " and " + std::to_string(found.size() - 5) + " more";
      throw scene::InputError("error: --out " + out.string() +
                              ": not empty and holds no sweep.plan.json (not a sweep directory): " +
                              names + "; use another --out, or --overwrite to write into it");
    }
    if (overwrite) remove_sweep_files(out);
  }
  // Before anything of a killed run is removed: a running one's temporaries are not a killed
  // run's. An unsharded sweep owns every point: it runs alone. Shards share the directory.
  claim.running = lock(out / kRunningLock,
                       shard.sharded() ? sys::FileLock::Mode::shared : sys::FileLock::Mode::exclusive,
                       false);
  if (!claim.running.held()) {
    throw running_elsewhere(shard.sharded() ? "an unsharded stiction sweep"
                                            : "another stiction sweep (or a shard of one)");
  }
  if (shard.sharded()) {
    claim.shard = lock(out / shard_lock_name(shard), sys::FileLock::Mode::exclusive, false);
    if (!claim.shard.held()) {
      throw running_elsewhere("shard " + std::to_string(shard.index) +
                              " of this sweep, started twice,");
    }
  }
  // What a killed run of this shard left (by its names only: other shards may be running).
  std::string table_prefix(1, '.');  // appended: GCC 12's -Wrestrict misfires on "." + s + "."
  table_prefix.append(table_name(shard)).append(".tmp-");
  std::vector<std::string> prefixes{table_prefix};
  if (!shard.sharded()) {
    for (const char* name : {".sweep.md.tmp-", ".sweep.png.tmp-", ".sweep.svg.tmp-"})
      prefixes.emplace_back(name);
  }
  remove_temporaries(out, prefixes);
  if (fs::is_directory(fs::symlink_status(out / "points", ec))) {
    for (const auto& entry : fs::directory_iterator(out / "points", ec)) {
      const auto index = point_index(entry.path().filename().string());
      if (index && shard.owns(*index)) remove_temporaries(entry.path());
    }
  }
  if (!fs::exists(fs::symlink_status(path, ec)) || read_text(path) != text)
    io::write_file_atomically(path, text);
  return claim;
}

SweepTable resume_sweep_table(const SweepPlan& plan, const fs::path& path, const Shard& shard,
                              bool force_step) {
  SweepTable table = read_sweep_table(path);
  if (!table.header.empty() && table.header != plan.columns) {
    throw scene::InputError("error: " + path.string() +
                            " has other columns than this sweep; use another --out or remove it");
  }
  table.header = plan.columns;
  // Keep only rows this shard owns whose values are the plan's (resume).
  for (auto it = table.rows.begin(); it != table.rows.end();) {
    bool keep = it->first < plan.points.size() && shard.owns(it->first);
    for (std::size_t k = 0; keep && k < plan.keys.size(); ++k) {
      keep = it->second[1 + k] == plan.points[it->first].values[k];
    }
    it = keep ? std::next(it) : table.rows.erase(it);
  }
  // With --force-step, points the guard refused before are run now (their note says so).
  if (force_step) {
    const std::size_t status_column = 1 + plan.keys.size();
    for (auto it = table.rows.begin(); it != table.rows.end();) {
      it = it->second[status_column] == "refused" ? table.rows.erase(it) : std::next(it);
    }
  }
  write_sweep_table(table, path);  // drops a row cut short by an interruption
  return table;
}

bool write_sweep(const SweepPlan& plan, const SweepTable& table, const fs::path& dir, bool overwrite) {
  const SweepClaim claim = claim_sweep_directory(plan, dir, Shard{}, overwrite);
  io::write_file_atomically(dir / "sweep.plan.json", plan.to_json());
  write_sweep_table(table, dir / "sweep.csv");
  return write_sweep_report(plan, table, dir);
}

SweepMerge merge_sweep_shards(const fs::path& dir) {
  const SweepPlan plan =
      SweepPlan::from_json(read_text(dir / "sweep.plan.json"), dir / "sweep.plan.json");
  SweepMerge merge;
  merge.points = plan.points.size();
  SweepTable merged;
  merged.header = plan.columns;
  std::vector<int> seen(plan.points.size(), 0);
  std::vector<fs::path> shards;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("sweep.shard-", 0) == 0 && entry.path().extension() == ".csv") {
      shards.push_back(entry.path());
    }
  }
  std::sort(shards.begin(), shards.end());
  if (shards.empty()) throw io::IoError(dir.string() + ": no sweep.shard-K.csv to merge");
  merge.shards = shards.size();
  for (const fs::path& shard : shards) {
    const SweepTable t = read_sweep_table(shard);
    if (t.header != plan.columns) {
      throw io::IoError(shard.string() + ": its columns differ from sweep.plan.json");
    }
    for (std::size_t index : t.repeated) {
      if (index < seen.size()) ++seen[index];
    }
    for (const auto& [index, row] : t.rows) {
      if (index >= plan.points.size()) {
        merge.problems.push_back(shard.filename().string() + ": point " + std::to_string(index) +
                                 " is beyond the sweep's " + std::to_string(plan.points.size()));
        continue;
      }
      for (std::size_t k = 0; k < plan.keys.size(); ++k) {
        if (row[1 + k] != plan.points[index].values[k]) {
          merge.problems.push_back(shard.filename().string() + ": point " + std::to_string(index) +
                                   " has other values than the plan");
        }
      }
      if (++seen[index] == 1) merged.rows[index] = row;
    }
  }
  for (std::size_t i = 0; i < seen.size(); ++i) {
    if (seen[i] == 0 && ++merge.missing <= 10)
      merge.problems.push_back("point " + std::to_string(i) + " is missing");
    if (seen[i] > 1 && ++merge.duplicated <= 10) {
      merge.problems.push_back("point " + std::to_string(i) + " is in " + std::to_string(seen[i]) +
                               " shards");
    }
  }
  if (!merge.problems.empty()) return merge;
  write_sweep_table(merged, dir / "sweep.csv");
  write_sweep_report(plan, merged, dir);
  return merge;
}

}  // namespace stiction::services
