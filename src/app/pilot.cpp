#include "app/pilot.hpp"

#include <algorithm>
#include <cmath>

namespace stiction::app {

Pilot bounded_pilot(core::Network& network, const core::RunOptions& run, double budget_seconds) {
  // Never more steps than this, whatever the measured speed (a counter that stays exact).
  constexpr double kMaxSteps = 2e6;
  constexpr double kProbeSteps = 256;
  Pilot pilot{run, false};
  pilot.options.stop = nullptr;
  core::RunOptions probe = run;
  probe.stop = nullptr;
  probe.duration = std::min(run.duration, kProbeSteps * run.dt);
  probe.output_rate = 1.0 / probe.duration;  // two rows: the probe is only timed
  const core::RunResult timed = core::simulate(network, probe);
  const double per_step = timed.wall_seconds / std::max(1L, timed.steps);
  // sample_states walks the run twice and classifies every state: about three runs' cost.
  double steps = per_step > 0.0 ? budget_seconds / (3.0 * per_step) : kMaxSteps;
  steps = std::clamp(steps, kProbeSteps, kMaxSteps);
  if (run.duration / run.dt > steps) {
    pilot.options.duration = steps * run.dt;
    pilot.shortened = true;
  }
  return pilot;
}

}  // namespace stiction::app
