// How accurate a run is (issue 26 item 3, issue 35; docs/accuracy.md): a companion run of the
// same scene at a finer setting, compared with the run by the one comparison of two runs
// (run_comparison.hpp), gives an estimated error of every event time and every final value,
// and a verdict on the quantities the scene judges. Fixed-step integrators: the companion
// takes half the step; Richardson's estimate with the integrator's order p for final values,
// (y_h - y_{h/2}) 2^p / (2^p - 1), and with order 1 for event times (their order is not the
// integrator's). An adaptive integrator: the companion runs at a tolerance 100 times tighter,
// and the difference is the estimate.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/simulation.hpp"
#include "scene/scene.hpp"
#include "services/run_comparison.hpp"

namespace stiction::services {

// The step limits `check` predicts for the run's integrator, when known (the caller wires
// them; the companion never takes a coarser step than the run, so they only inform: JSON
// `step_limits`).
struct PredictedStepLimits {
  std::optional<double> chatter_limit;
  std::optional<double> instability_limit;
};

enum class AccuracyMode { automatic, on, off };

// The verdict's tolerances and the rule for `automatic` (docs/accuracy.md).
struct AccuracySettings {
  AccuracyMode mode = AccuracyMode::automatic;
  // automatic: on when the companion's expected cost is at most this (CPU seconds).
  double budget_seconds = 5.0;
  // What is judged and the tolerances (run_comparison.hpp); empty: the scene's [accuracy].
  std::optional<JudgeRule> rule;
};

struct EventAccuracy {
  std::string kind;
  double time = 0.0;
  std::optional<double> error;  // none when this event has no counterpart in the companion
  double located = 0.0;         // how precisely the run located it (core::SlipEvent)
  bool judged = false;          // the first or last of its kind, judged by the rule
};

struct FinalAccuracy {
  std::string column;
  double value = 0.0;
  double error = 0.0;
  double scale = 0.0;   // largest magnitude of the signal over the companion run
  bool judged = false;  // a body's signal: it counts for the verdict
};

struct ElementEvents {
  std::string element;
  std::vector<EventAccuracy> events;
};

struct AccuracyEstimate {
  std::string method;  // "richardson", "tighter_tolerance" or "off"
  std::string reason;  // why off, or why it was on by default
  int order = 0;       // the integrator's order (richardson)
  std::string companion_integrator;
  double companion_dt = 0.0;
  std::optional<double> companion_tolerance;
  std::vector<ElementEvents> events;
  std::vector<FinalAccuracy> finals;
  std::string verdict = "unknown";  // "accurate", "inaccurate" or "unknown"
  std::vector<std::string> reasons;
  RunComparison comparison;  // the judged quantities, tolerances and unconverged counts
  JudgeRule rule;
  double cpu_seconds = 0.0;      // what the companion cost
  bool interrupted = false;      // the companion was stopped by a signal
  PredictedStepLimits limits;    // as passed in; in the JSON (`step_limits`) when known
};

// The companion's expected CPU cost relative to the run: 2 for half the step; for an
// adaptive integrator at tolerance / 100, 100^(1/q) with q its traits' error_order (its
// steps scale as tolerance^(1/q): rk4_adaptive 100^(1/5), sdirk2 100^(1/2), sdirk4
// 100^(1/4)).
double companion_cost_factor(const core::RunOptions& run);

// The companion of `run`: half the step, or an adaptive integrator's tolerance / 100, with
// the run's event resolution; and the comparison of the run with it (Richardson factors with
// the integrator's order for final values, 2 for event times). Every command that judges a
// step's accuracy (run, check's and the guard's trials, study's confirmation) uses these.
core::RunOptions companion_options(const core::RunOptions& run);
ComparisonSetup companion_setup(const core::RunOptions& run, JudgeRule rule);

// Runs the companion (with scene.run's stop flag) and compares (run_comparison.hpp). `result` is the finished,
// stable and uninterrupted run of scene.run; its trajectory's last row holds the final
// values. With mode off, or automatic over the budget, nothing is simulated.
AccuracyEstimate estimate_accuracy(scene::Scene& scene, const core::RunResult& result,
                                   const PredictedStepLimits& limits,
                                   const AccuracySettings& settings = {});

// summary.json `accuracy` (docs/command_line.md).
nlohmann::ordered_json accuracy_json(const AccuracyEstimate& estimate);

// The warning for an inaccurate run (stderr): the step, the reasons, where to look.
void print_inaccurate(const std::string& scene_name, const core::RunOptions& run,
                      const AccuracyEstimate& estimate);

}  // namespace stiction::services
