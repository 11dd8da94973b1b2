// What `run` and `compare` share: applying command-line overrides to a scene's run options,
// simulating with a progress bar, the events a plot marks, Ctrl-C handling while rendering.
#pragma once

#include <atomic>
#include <map>
#include <optional>
#include <string>

#include <signal.h>

#include "core/simulation.hpp"
#include "scene/scene.hpp"

namespace stiction::app {

struct RunOverrides {
  std::optional<std::string> integrator;
  std::optional<double> dt;
  std::optional<double> duration;
  std::optional<double> tolerance;  // selects rk4_adaptive
};

// Applies the overrides to scene.run. scene::InputError (exit 2) when --tolerance meets a
// fixed-step --integrator, or rk4_adaptive ends up without a tolerance.
void apply_overrides(scene::Scene& scene, const RunOverrides& overrides);

// True when progress should be drawn: stderr is a terminal and --quiet was not given.
bool show_progress(bool quiet);

// core::simulate with a progress bar on stderr when `progress` is set.
// With a sink, rows stream to it (core::simulate).
core::RunResult simulate_scene(scene::Scene& scene, bool progress, core::RowSink* sink = nullptr);

// "<impedance>.stick_time" -> first stick time, for every element that stuck.
std::map<std::string, double> event_times(const core::RunResult& result);

// The step to suggest after an instability: 0.8 times the largest stable step predicted by
// linearizing the step map along a pilot run at a quarter of the step (core/stability.hpp),
// when that is below the failed step; a quarter of the step otherwise.
double suggested_dt(scene::Scene& scene);

// The error line for an unstable run (stderr), naming the time, the component and a step
// (for rk4_adaptive a tolerance instead).
void print_instability(const std::string& scene_name, const core::RunOptions& run,
                       const core::Instability& instability, double suggested_dt);

// While alive, SIGINT sets `flag` instead of killing the process (a second Ctrl-C kills as
// usual: the handler resets itself). The previous handler is restored on destruction.
class InterruptFlag {
 public:
  explicit InterruptFlag(std::atomic<bool>& flag);
  ~InterruptFlag();
  InterruptFlag(const InterruptFlag&) = delete;
  InterruptFlag& operator=(const InterruptFlag&) = delete;

 private:
  struct sigaction previous_ {};
  bool installed_ = false;
};

}  // namespace stiction::app
