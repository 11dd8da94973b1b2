// `stiction sweep`: parses the sweep's arguments, runs its points through the services
// (services/sweep_run.hpp) into its directory (services/sweep_directory.hpp: the plan, the
// table appended row by row so that re-running after an interruption skips the finished
// points, the report, the merge of shards) and prints what it did.
#include "services/sweep.hpp"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "app/commands.hpp"
#include "scene/scene.hpp"
#include "services/sweep_directory.hpp"
#include "services/sweep_run.hpp"
#include "sys/interrupt.hpp"

namespace stiction::app {
using namespace services;
namespace fs = std::filesystem;
namespace {

int merge(const fs::path& dir, bool quiet) {
  const SweepMerge merged = merge_sweep_shards(dir);
  if (!merged.problems.empty()) {
    std::fprintf(stderr, "error: %s: cannot merge (%zu missing, %zu in several shards):\n",
                 dir.c_str(), merged.missing, merged.duplicated);
    for (const std::string& p : merged.problems) std::fprintf(stderr, "  %s\n", p.c_str());
    return kExitFailure;
  }
  if (!quiet) {
    std::printf("merged %zu shards: %zu points, every one exactly once\n  wrote %s\n",
                merged.shards, merged.points, (dir / "sweep.csv").c_str());
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
  SweepSettings settings;
  settings.scene = args.scene;
  settings.overrides = args.overrides;
  settings.run = {args.integrator, args.dt, args.duration, args.tolerance};
  settings.force_step = args.force_step;
  settings.keep = args.keep;

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

  const SweepSignals signals = complete_sweep_plan(plan, settings, args.record, args.plot);

  const fs::path out =
      args.out.empty() ? fs::path("out") / signals.scene_name / "sweep" : fs::path(args.out);
  // Held until the sweep ends: no other sweep writes here meanwhile.
  const SweepClaim claim = claim_sweep_directory(plan, out, shard, args.overwrite);

  const fs::path table_path = shard.sharded()
                                  ? out / ("sweep.shard-" + std::to_string(shard.index) + ".csv")
                                  : out / "sweep.csv";
  SweepTable table = resume_sweep_table(plan, table_path, shard, args.force_step);
  const std::size_t resumed = table.rows.size();

  const std::vector<const SweepPoint*> todo = points_to_run(plan, table, shard);
  const unsigned jobs = sweep_threads(args.jobs, todo.size());
  const bool progress = show_progress(args.quiet);
  if (!args.quiet) {
    std::printf("sweep %s: %zu points%s, %zu to run (%zu done before) on %u threads\n",
                signals.scene_name.c_str(), plan.points.size(),
                shard.sharded() ? (" (shard " + std::to_string(shard.index) + "/" +
                                   std::to_string(shard.count) + ")")
                                      .c_str()
                                : "",
                todo.size(), resumed, jobs);
    std::fflush(stdout);
  }

  SweepAppender appender(table_path, plan.columns);
  // On a terminal one line rewritten in place; in a log (a batch job's stderr) plain lines at
  // every 10% or 10 s, as `run`'s progress (DESIGN section 3): carriage returns would pile up
  // in the file as one unreadable line.
  const bool terminal = ::isatty(STDERR_FILENO) == 1;
  const auto started = std::chrono::steady_clock::now();
  auto last_line = started;
  std::size_t last_tenth = 0;
  run_sweep_points(
      settings, plan, signals, out, todo, jobs, table,
      [&appender](const std::vector<std::string>& row) { appender.append(row); },
      [&](std::size_t finished) {
        if (!progress) return;
        if (terminal) {
          std::fprintf(stderr, "\r  %zu / %zu points", finished, todo.size());
          return;
        }
        const auto now = std::chrono::steady_clock::now();
        const std::size_t tenth = todo.empty() ? 10 : 10 * finished / todo.size();
        if (tenth > last_tenth || now - last_line >= std::chrono::seconds(10)) {
          std::fprintf(stderr, "  %zu / %zu points after %.1f s\n", finished, todo.size(),
                       std::chrono::duration<double>(now - started).count());
          last_tenth = tenth;
          last_line = now;
        }
      });
  if (progress && terminal) std::fprintf(stderr, "\n");

  write_sweep_table(table, table_path);
  std::size_t ok = 0;
  const std::size_t status = 1 + plan.keys.size();
  for (const auto& [index, row] : table.rows) ok += row[status] == "ok";
  if (sys::interrupted()) {
    // The table is consistent and resumable; the report (a figure of every point, seconds
    // for a large sweep) waits for the sweep to be complete.
    if (!args.quiet) {
      std::printf("  interrupted by %s after %zu points; wrote %s (run the same command to resume)\n",
                  sys::interrupt_signal_name(), table.rows.size(), table_path.c_str());
    }
    return sys::interrupt_exit_code();
  }
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
