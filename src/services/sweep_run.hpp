// Running the points of a sweep (docs/sweeps.md): every point is a full run of the scene
// loaded from its source with the shared overrides, then the point's values, simulated on a
// worker thread (each run owns its scene, network and expression parsers; nothing is shared
// but the read-only plan and the table, behind a mutex). A point that fails (instability, a
// value the loader rejects) is a row with its status, never the end of the sweep. The
// command line appends finished rows to its table file at once (sweep_directory.hpp); the
// Python module keeps them in memory.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "scene/scene.hpp"
#include "services/run_support.hpp"
#include "services/sweep.hpp"

namespace stiction::services {

// What every point of a sweep shares.
struct SweepSettings {
  scene::SceneSource scene;            // loaded afresh for every point
  std::vector<std::string> overrides;  // --set, applied before the point's values
  RunOverrides run;                    // --integrator, --dt, --duration, --tolerance
  bool force_step = false;             // simulate points the step guard predicts unstable
  std::string keep = "none";           // none | summary | all: per-point outputs (need a dir)
};

// What the first point's scene says about every point, and the signals tabled.
struct SweepSignals {
  std::string scene_name;
  std::vector<std::string> signals;          // the trajectory's columns after "t"
  std::vector<std::string> slip_components;  // elements with a slip speed: event columns
  std::vector<std::string> records;          // signals whose final value is tabled
};

// Loads the first point's scene and completes `plan` (its scene, keys, zip and points set):
// the table's columns and the columns to plot (`plot`, default every element's stick time
// and first slip). `records` empty: every signal. scene::InputError for a record that is no
// signal or a plot column that is not in the table, with the command line's messages.
SweepSignals complete_sweep_plan(SweepPlan& plan, const SweepSettings& settings,
                                 const std::vector<std::string>& records,
                                 const std::vector<std::string>& plot);

// The points of the plan that `shard` owns and `table` has no row for, in order.
std::vector<const SweepPoint*> points_to_run(const SweepPlan& plan, const SweepTable& table,
                                             const Shard& shard);

// Threads for `todo` points: `jobs` (0: every core), at least 1, at most one per point.
unsigned sweep_threads(int jobs, std::size_t todo);

// Runs `todo` on `jobs` threads into table.rows. `append` (may be empty) is called under the
// table's lock with each row before it enters the table (the command line's table file); its
// exception stops the sweep and is rethrown. `finished` (may be empty) after each row, under
// the lock, with the count so far. A signal (sys::interrupted()) stops the workers: the rows
// so far stay. `out`: the sweep's directory for the per-point outputs of settings.keep.
void run_sweep_points(const SweepSettings& settings, const SweepPlan& plan,
                      const SweepSignals& signals, const std::filesystem::path& out,
                      const std::vector<const SweepPoint*>& todo, unsigned jobs, SweepTable& table,
                      const std::function<void(const std::vector<std::string>&)>& append = {},
                      const std::function<void(std::size_t)>& finished = {});

}  // namespace stiction::services
