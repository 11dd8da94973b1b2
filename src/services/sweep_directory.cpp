#include "services/sweep_directory.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "io/atomic_file.hpp"
#include "scene/toml_reader.hpp"

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

void write_or_check_plan(const SweepPlan& plan, const fs::path& out) {
  const fs::path path = out / "sweep.plan.json";
  const std::string text = plan.to_json();
  std::error_code ec;
  if (fs::exists(path, ec)) {
    if (read_text(path) != text) {
      throw scene::InputError("error: " + path.string() +
                              " describes another sweep (other scene, keys, values or records); "
                              "use another --out or remove that directory");
    }
    return;
  }
  io::write_file_atomically(path, text);
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

bool write_sweep(const SweepPlan& plan, const SweepTable& table, const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw io::IoError(dir.string() + ": cannot create the directory: " + ec.message());
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
