// A run as a service: what `stiction run` does before it writes pictures, without printing
// (the command line and the Python module share it). In two steps so that a caller can act
// between them: prepare_run loads the settings the outputs need and applies the step guard
// (a refusal is returned, not printed), simulate_run simulates, estimates the accuracy and
// builds summary.json's content, then estimate_run_accuracy runs the companion.
#pragma once

#include <atomic>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/column_info.hpp"
#include "core/row_sink.hpp"
#include "core/simulation.hpp"
#include "plot/plot_spec.hpp"
#include "render/render_settings.hpp"
#include "scene/scene.hpp"
#include "services/accuracy.hpp"
#include "services/run_support.hpp"
#include "services/step_guard.hpp"

namespace stiction::services {

struct RunRequest {
  RunOverrides overrides;
  bool force_step = false;            // --force-step
  std::optional<bool> accuracy;       // --accuracy on|off; empty: on when it costs little
  bool check_frames = false;          // check the frame count now (a video or frames follow)
  bool progress = false;              // a progress bar (or lines) on stderr
  const std::atomic<bool>* stop = nullptr;  // polled: set -> the run stops, keeps its rows
};

// A scene loaded and checked, ready to simulate.
struct PreparedRun {
  scene::Scene scene;
  render::RenderSettings render_settings;
  std::vector<std::string> columns;  // "t" and every signal column
  std::vector<core::ColumnInfo> infos;
  std::vector<plot::PlotSpec> plot_specs;  // the scene's [[plots]] or the default figures
  std::vector<std::string> plots_not_drawn;  // signal groups beyond the default figures' cap
  std::vector<scene::Warning> warnings;    // the scene's, then the step guard's
  StepGuard guard;                          // guard.refusal set: do not simulate
  JudgeRule judge_rule;                     // [accuracy]: what the verdict judges
  bool dt_from_overrides = false;
};

// Applies the overrides, reads [render], [[plots]] and [verify] (InputError, exit 2, on a
// bad table).
PreparedRun prepare_run(scene::Scene scene, const RunRequest& request);
// The step guard (services/step_guard.hpp) on a prepared run: run.guard.refusal set means do
// not simulate; a warning is appended to run.warnings.
void guard_run(PreparedRun& run, const RunRequest& request);

struct RunOutcome {
  core::RunResult result;
  nlohmann::ordered_json summary;  // summary.json without `files` (and `status` of the run)
  AccuracyEstimate accuracy;
  std::optional<StepSuggestion> suggestion;  // after an instability
  double time_reached = 0.0;                 // time of the last row
  bool accuracy_interrupted = false;         // the signal came during the companion run
};

// Simulates (rows also to `sink` when given) and builds the summary. An interrupted or
// unstable run keeps its rows (see result.interrupted and result.instability); its summary's
// `accuracy` says why there is no estimate.
RunOutcome simulate_run(PreparedRun& run, const RunRequest& request, core::RowSink* sink = nullptr);
// The error estimate of a finished run (docs/accuracy.md: a companion run), into the summary;
// nothing for an unstable or interrupted one. A step of its own so that a caller can first
// keep the rows (the command commits trajectory.csv before the companion runs).
void estimate_run_accuracy(PreparedRun& run, const RunRequest& request, RunOutcome& outcome);

}  // namespace stiction::services
