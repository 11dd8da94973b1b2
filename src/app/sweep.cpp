// `stiction sweep`: every point is a full run of the scene with its --set values, loaded and
// simulated on a worker thread (each run owns its scene, network and expression parsers;
// nothing is shared but the read-only plan and the table, behind a mutex). A point that
// fails (instability, a value the loader rejects) is a row with its status, never the end of
// the sweep. Finished rows are appended to the table file at once, so re-running after an
// interruption skips them.
#include "services/sweep.hpp"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <fstream>
#include <mutex>
#include <sstream>
#include <thread>

#include "app/commands.hpp"
#include "services/run_support.hpp"
#include "services/step_guard.hpp"
#include "core/simulation.hpp"
#include "io/atomic_file.hpp"
#include "io/csv_writer.hpp"
#include "io/summary.hpp"
#include "scene/scene.hpp"
#include "sys/interrupt.hpp"

namespace stiction::app {
using namespace services;
namespace fs = std::filesystem;
namespace {

std::string number_text(double v) {
  std::string s;
  io::append_number(s, v);
  return s;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw io::IoError(path.string() + ": cannot read");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

std::vector<std::string> point_overrides(const SweepArguments& args, const SweepPlan& plan,
                                         const SweepPoint& point) {
  std::vector<std::string> overrides = args.overrides;
  for (std::size_t k = 0; k < plan.keys.size(); ++k) {
    overrides.push_back(plan.keys[k].key + "=" + point.values[k]);
  }
  return overrides;
}

// What the first point's scene says about every point: its name, signals and contacts.
struct Probe {
  std::string name;
  std::vector<std::string> signals;
  std::vector<std::string> slip_components;
};

Probe probe_scene(const SweepArguments& args, const SweepPlan& plan) {
  scene::Scene scene =
      scene::load_scene(args.scene, point_overrides(args, plan, plan.points.front()));
  apply_overrides(scene, {args.integrator, args.dt, args.duration, args.tolerance});
  Probe probe;
  probe.name = scene.name;
  probe.signals = scene.network->signal_columns();
  const core::Network& network = *scene.network;
  for (int i = 0; i < static_cast<int>(network.impedances().size()); ++i) {
    if (network.capabilities(i).slip != nullptr) {
      probe.slip_components.push_back(network.impedances()[i]->name());
    }
  }
  return probe;
}

class DiscardRows final : public core::RowSink {
 public:
  void write(const double*, std::size_t, std::size_t) override {}
};

// Wall-clock seconds the trial runs behind one point's suggested step may take: a sweep has
// many points, so less than `run` allows.
constexpr double kSuggestionBudget = 5.0;

class PointRunner {
 public:
  PointRunner(const SweepArguments& args, const SweepPlan& plan, const Probe& probe,
              const std::vector<std::string>& records, const fs::path& out)
      : args_(args), plan_(plan), probe_(probe), records_(records), out_(out) {}

  // The point's table row; empty when a signal stopped it before it had one.
  std::vector<std::string> run(const SweepPoint& point) const {
    std::vector<std::string> row(plan_.columns.size());
    row[0] = std::to_string(point.index);
    for (std::size_t k = 0; k < point.values.size(); ++k) row[1 + k] = point.values[k];
    const std::size_t base = 1 + point.values.size();  // status, steps, wall_s, suggested_dt, note
    try {
      scene::Scene scene = scene::load_scene(args_.scene, point_overrides(args_, plan_, point));
      apply_overrides(scene, {args_.integrator, args_.dt, args_.duration, args_.tolerance});
      if (scene.network->signal_columns() != probe_.signals) {
        row[base] = "error";
        row[base + 4] = "the values of this point change the scene's signals";
        return row;
      }
      // The step guard, per point (the values may move the limits): a point predicted
      // unstable is not simulated; its row says so and suggests a step.
      const StepGuard guard = guard_step(scene, args_.force_step, kSuggestionBudget);
      if (guard.refusal) {
        row[base] = "refused";
        row[base + 3] = number_text(guard.refusal->dt);
        row[base + 4] = "not simulated: " + step_check_text(guard.check) + "; try --dt " +
                        number_text(guard.refusal->dt) + " (--force-step runs it anyway)";
        return row;
      }
      // Rows stream to the point's trajectory.csv (--keep all) or nowhere: the table needs
      // only the last row, which the result keeps. A signal stops the point: no row for it.
      scene.run.stop = &sys::interrupt_flag();
      core::RunResult result;
      if (args_.keep == "all") {
        std::vector<std::string> columns = probe_.signals;
        columns.insert(columns.begin(), "t");
        fs::create_directories(point_dir(point));
        io::CsvStream csv(point_dir(point) / "trajectory.csv", columns);
        result = core::simulate(*scene.network, scene.run, {}, &csv);
        if (!result.interrupted) csv.commit();  // else no complete-looking file
      } else {
        DiscardRows none;
        result = core::simulate(*scene.network, scene.run, {}, &none);
      }
      if (result.interrupted) return {};
      row[base + 1] = std::to_string(result.steps);
      char wall[32];
      std::snprintf(wall, sizeof wall, "%.4g", result.wall_seconds);
      row[base + 2] = wall;
      if (result.instability) {
        const double dt = suggest_step(scene, guard.check, kSuggestionBudget).dt;
        row[base] = "unstable";
        row[base + 3] = number_text(dt);
        row[base + 4] = "instability at t = " + number_text(result.instability->time) + " s in '" +
                        result.instability->component + "' (" + result.instability->reason +
                        "); try --dt " + number_text(dt);
      } else {
        row[base] = "ok";
        if (guard.warning) row[base + 4] = "step check: " + *guard.warning;
      }
      std::size_t c = base + 5;
      for (const core::SlipHistory& h : result.slip_events) {
        for (const double time :
             {h.monitor.stick_time(), h.monitor.first_slip(), h.monitor.last_stick()}) {
          row[c++] = time >= 0.0 ? number_text(time) : "";
        }
        std::string events;
        for (const core::SlipEvent& e : h.monitor.events()) {
          events += (events.empty() ? "" : ";") + e.kind + ":" + number_text(e.time);
        }
        row[c++] = events;
      }
      const core::Trajectory& tr = result.trajectory;
      for (const std::string& record : records_) {
        const int col = *tr.find(record);
        row[c++] = tr.row_count() > 0 ? number_text(tr.at(tr.row_count() - 1, col)) : "";
      }
      keep(point, scene, result, guard.check);
    } catch (const sys::Interrupted&) {
      return {};  // a signal during the step check or a suggestion's trials: no row
    } catch (const scene::InputError& e) {
      row[base] = "error";
      row[base + 4] = e.what();
    } catch (const std::exception& e) {
      row[base] = "error";
      row[base + 4] = e.what();
    }
    return row;
  }

 private:
  fs::path point_dir(const SweepPoint& point) const {
    char leaf[32];
    std::snprintf(leaf, sizeof leaf, "%06zu", point.index);
    return out_ / "points" / leaf;
  }

  void keep(const SweepPoint& point, const scene::Scene& scene, const core::RunResult& result,
            const StepCheck& check) const {
    if (args_.keep == "none") return;
    const fs::path dir = point_dir(point);
    fs::create_directories(dir);
    auto summary = io::make_summary(describe_run(scene), result);
    summary["step_check"] = step_check_json(check);
    summary["accuracy"] = {{"method", "off"},
                           {"reason",
                            "a sweep point estimates no accuracy (run the point "
                            "with `stiction run` for its error bars)"}};
    summary["warnings"] = warnings_json(scene.warnings);
    io::write_summary(summary, dir / "summary.json");
  }

  const SweepArguments& args_;
  const SweepPlan& plan_;
  const Probe& probe_;
  const std::vector<std::string>& records_;
  fs::path out_;
};

// The plan a directory already holds must be this one: shards of one sweep share it.
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

int merge(const fs::path& dir, bool quiet) {
  const SweepPlan plan =
      SweepPlan::from_json(read_text(dir / "sweep.plan.json"), dir / "sweep.plan.json");
  SweepTable merged;
  merged.header = plan.columns;
  std::vector<int> seen(plan.points.size(), 0);
  std::vector<std::string> problems;
  std::vector<fs::path> shards;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("sweep.shard-", 0) == 0 && entry.path().extension() == ".csv") {
      shards.push_back(entry.path());
    }
  }
  std::sort(shards.begin(), shards.end());
  if (shards.empty()) throw io::IoError(dir.string() + ": no sweep.shard-K.csv to merge");
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
        problems.push_back(shard.filename().string() + ": point " + std::to_string(index) +
                           " is beyond the sweep's " + std::to_string(plan.points.size()));
        continue;
      }
      for (std::size_t k = 0; k < plan.keys.size(); ++k) {
        if (row[1 + k] != plan.points[index].values[k]) {
          problems.push_back(shard.filename().string() + ": point " + std::to_string(index) +
                             " has other values than the plan");
        }
      }
      if (++seen[index] == 1) merged.rows[index] = row;
    }
  }
  std::size_t missing = 0, duplicated = 0;
  for (std::size_t i = 0; i < seen.size(); ++i) {
    if (seen[i] == 0 && ++missing <= 10)
      problems.push_back("point " + std::to_string(i) + " is missing");
    if (seen[i] > 1 && ++duplicated <= 10) {
      problems.push_back("point " + std::to_string(i) + " is in " + std::to_string(seen[i]) +
                         " shards");
    }
  }
  if (!problems.empty()) {
    std::fprintf(stderr, "error: %s: cannot merge (%zu missing, %zu in several shards):\n",
                 dir.c_str(), missing, duplicated);
    for (const std::string& p : problems) std::fprintf(stderr, "  %s\n", p.c_str());
    return kExitFailure;
  }
  write_sweep_table(merged, dir / "sweep.csv");
  write_sweep_report(plan, merged, dir);
  if (!quiet) {
    std::printf("merged %zu shards: %zu points, every one exactly once\n  wrote %s\n",
                shards.size(), plan.points.size(), (dir / "sweep.csv").c_str());
  }
  return kExitOk;
}

}  // namespace

int sweep_command(const SweepArguments& args) {
  if (!args.merge.empty()) return merge(args.merge, args.quiet);
  if (args.scene.empty())
    throw scene::InputError("error: sweep: a SCENE is needed (or --merge DIR)");
  if (args.vary.empty())
    throw scene::InputError("error: sweep: at least one --vary KEY=LIST is needed");
  if (args.keep != "none" && args.keep != "summary" && args.keep != "all") {
    throw scene::InputError("error: --keep: expected none, summary or all");
  }
  SweepPlan plan;
  plan.scene = args.scene;
  plan.zip = args.zip;
  for (const std::string& v : args.vary) plan.keys.push_back(parse_vary(v));
  plan.points = make_points(plan.keys, args.zip);

  Shard shard;
  if (!args.shard.empty()) {
    shard = parse_shard(args.shard);
  } else if (auto from_env = shard_from_environment()) {
    shard = *from_env;
  }

  const Probe probe = probe_scene(args, plan);
  std::vector<std::string> records = args.record.empty() ? probe.signals : args.record;
  for (const std::string& r : records) {
    if (std::find(probe.signals.begin(), probe.signals.end(), r) == probe.signals.end()) {
      std::string known;
      for (const std::string& s : probe.signals) known += " " + s;
      throw scene::InputError("error: --record " + r + ": not a signal of " + probe.name +
                              "; its signals are:" + known);
    }
  }
  plan.columns = {"point"};
  for (const VaryKey& k : plan.keys) plan.columns.push_back(k.key);
  for (const char* c : {"status", "steps", "wall_s", "suggested_dt", "note"})
    plan.columns.push_back(c);
  for (const std::string& c : probe.slip_components) {
    for (const char* event : {".stick_time", ".first_slip", ".last_stick", ".events"})
      plan.columns.push_back(c + event);
  }
  for (const std::string& r : records) plan.columns.push_back(r);
  if (!args.plot.empty()) {
    for (const std::string& p : args.plot) {
      if (std::find(plan.columns.begin(), plan.columns.end(), p) == plan.columns.end()) {
        throw scene::InputError("error: --plot " + p + ": not a column of the sweep table");
      }
    }
    plan.plot = args.plot;
  } else {
    // Every element's first stick and first slip; the report leaves out those no point has
    // and falls back to the first record (plotted_columns).
    for (const std::string& c : probe.slip_components) {
      plan.plot.push_back(c + ".stick_time");
      plan.plot.push_back(c + ".first_slip");
    }
  }

  const fs::path out =
      args.out.empty() ? fs::path("out") / probe.name / "sweep" : fs::path(args.out);
  fs::create_directories(out);
  write_or_check_plan(plan, out);

  const fs::path table_path = shard.sharded()
                                  ? out / ("sweep.shard-" + std::to_string(shard.index) + ".csv")
                                  : out / "sweep.csv";
  SweepTable table = read_sweep_table(table_path);
  if (!table.header.empty() && table.header != plan.columns) {
    throw scene::InputError("error: " + table_path.string() +
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
  if (args.force_step) {
    const std::size_t status_column = 1 + plan.keys.size();
    for (auto it = table.rows.begin(); it != table.rows.end();) {
      it = it->second[status_column] == "refused" ? table.rows.erase(it) : std::next(it);
    }
  }
  const std::size_t resumed = table.rows.size();
  write_sweep_table(table, table_path);  // drops a row cut short by an interruption

  std::vector<const SweepPoint*> todo;
  for (const SweepPoint& p : plan.points) {
    if (shard.owns(p.index) && table.rows.count(p.index) == 0) todo.push_back(&p);
  }
  unsigned jobs =
      args.jobs > 0 ? static_cast<unsigned>(args.jobs) : std::thread::hardware_concurrency();
  jobs = std::max(
      1u, std::min<unsigned>(jobs, static_cast<unsigned>(std::max<std::size_t>(1, todo.size()))));
  const bool progress = show_progress(args.quiet);
  if (!args.quiet) {
    std::printf("sweep %s: %zu points%s, %zu to run (%zu done before) on %u threads\n",
                probe.name.c_str(), plan.points.size(),
                shard.sharded() ? (" (shard " + std::to_string(shard.index) + "/" +
                                   std::to_string(shard.count) + ")")
                                      .c_str()
                                : "",
                todo.size(), resumed, jobs);
    std::fflush(stdout);
  }

  PointRunner runner(args, plan, probe, records, out);
  SweepAppender appender(table_path, plan.columns);
  std::mutex mutex;
  std::atomic<std::size_t> next{0};
  std::size_t finished = 0;
  std::exception_ptr failure;
  auto work = [&] {
    for (std::size_t i = next++; i < todo.size(); i = next++) {
      if (sys::interrupted()) return;  // SIGINT/SIGTERM: the rows so far stay, resumable
      std::vector<std::string> row = runner.run(*todo[i]);
      if (row.empty()) return;
      std::lock_guard<std::mutex> lock(mutex);
      try {
        appender.append(row);
      } catch (...) {
        if (!failure) failure = std::current_exception();
        next = todo.size();
        return;
      }
      table.rows[todo[i]->index] = std::move(row);
      ++finished;
      if (progress) std::fprintf(stderr, "\r  %zu / %zu points", finished, todo.size());
    }
  };
  std::vector<std::thread> threads;
  for (unsigned j = 1; j < jobs; ++j) threads.emplace_back(work);
  work();
  for (auto& t : threads) t.join();
  if (progress) std::fprintf(stderr, "\n");
  if (failure) std::rethrow_exception(failure);

  write_sweep_table(table, table_path);
  std::size_t ok = 0;
  const std::size_t status = 1 + plan.keys.size();
  for (const auto& [index, row] : table.rows) ok += row[status] == "ok";
  const bool figure = !shard.sharded() && write_sweep_report(plan, table, out);
  if (!args.quiet) {
    std::printf("  %zu ok, %zu unstable or failed\n  wrote %s\n", ok, table.rows.size() - ok,
                table_path.c_str());
    if (shard.sharded()) {
      std::printf("  when every shard is done: stiction sweep --merge %s\n", out.c_str());
    } else if (figure) {
      std::printf("  wrote %s, %s and %s\n", (out / "sweep.md").c_str(),
                  (out / "sweep.png").c_str(), (out / "sweep.svg").c_str());
    } else {
      std::printf("  wrote %s (no column has a value to plot)\n", (out / "sweep.md").c_str());
    }
  }
  return kExitOk;
}

}  // namespace stiction::app
