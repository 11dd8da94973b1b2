// What `run` and `compare` share: applying command-line overrides to a scene's run options,
// simulating with a progress bar, the events a plot marks (signals: sys/interrupt.hpp).
#pragma once

#include <atomic>
#include <map>
#include <optional>
#include <string>

#include "services/suggest_step.hpp"
#include "core/simulation.hpp"
#include "io/summary.hpp"
#include "scene/scene.hpp"

namespace stiction::services {

// What summary.json says of the scene's run (scene, integrator, step, duration, output rate,
// state size, tolerance); `run` adds the column descriptions.
io::RunDescription describe_run(const scene::Scene& scene);

struct RunOverrides {
  std::optional<std::string> integrator;
  std::optional<double> dt;
  std::optional<double> duration;
  std::optional<double> tolerance;  // an adaptive integrator's (rk4_adaptive by default)
};

// Applies the overrides to scene.run. scene::InputError (exit 2) when --tolerance meets a
// fixed-step --integrator, or rk4_adaptive ends up without a tolerance.
void apply_overrides(scene::Scene& scene, const RunOverrides& overrides);

// True when progress should be shown (a bar on a terminal, plain lines otherwise): unless
// --quiet was given.
bool show_progress(bool quiet);

// core::simulate with a progress bar on stderr when `progress` is set.
// With a sink, rows stream to it (core::simulate).
core::RunResult simulate_scene(scene::Scene& scene, bool progress, core::RowSink* sink = nullptr);

// "<impedance>.stick_time" -> first stick time, for every element that stuck, and
// "<impedance>.slip_time" -> first slip time, for every element that slipped.
std::map<std::string, double> event_times(const core::RunResult& result);

// The step to suggest after an instability, checked by trial runs (app/suggest_step.hpp),
// from the run's step check.
StepSuggestion suggested_dt(scene::Scene& scene, const StepCheck& check);

// The error line for an unstable run (stderr), naming the time, the component and a step
// with how it was obtained (for rk4_adaptive a tolerance instead).
void print_instability(const std::string& scene_name, const core::RunOptions& run,
                       const core::Instability& instability, const StepSuggestion& suggestion);

}  // namespace stiction::services
