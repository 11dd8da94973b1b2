// How accurate a run is (issue 26, item 3; docs/accuracy.md): a companion run of the same
// scene at a finer setting, and from the two an estimated error of every event time and of
// every final value, with a verdict. Fixed-step integrators: the companion takes half the
// step and Richardson's estimate with the integrator's order p gives the error of the run,
// (y_h - y_{h/2}) 2^p / (2^p - 1). rk4_adaptive: the companion runs at a tolerance 100 times
// tighter, and the difference is the estimate. Events are matched per element and kind in
// order; a different number of events in the two runs means the step decides the event
// sequence: the run is inaccurate whatever the numbers say.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/simulation.hpp"
#include "scene/scene.hpp"

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
  // An event time's error above this fraction of the duration makes the run inaccurate.
  double event_tolerance = 1e-3;
  // A body's final value with an error above this fraction of its signal's scale (the
  // largest magnitude of the signal, all its axes, over the companion run) likewise.
  double final_tolerance = 1e-3;
};

struct EventAccuracy {
  std::string kind;
  double time = 0.0;
  std::optional<double> error;  // none when the two runs' events of this kind differ
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
  double cpu_seconds = 0.0;      // what the companion cost
  bool interrupted = false;      // the companion was stopped by a signal
  double event_tolerance = 0.0;  // seconds
  double final_tolerance = 0.0;  // relative to the scale
  PredictedStepLimits limits;    // as passed in; in the JSON (`step_limits`) when known
};

// The companion's expected CPU cost relative to the run: 2 for half the step; for
// rk4_adaptive at tolerance / 100, 100^(1/5) (the local error is O(h^5)).
double companion_cost_factor(const core::RunOptions& run);

// Runs the companion (with scene.run's stop flag) and compares. `result` is the finished,
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
