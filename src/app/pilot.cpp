#include "app/pilot.hpp"

#include <algorithm>
#include <cmath>

namespace stiction::app {

double round_down_125(double x) {
  const double decade = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {5.0, 2.0, 1.0}) {
    if (m * decade <= x * (1.0 + 1e-12)) return m * decade;
  }
  return decade;
}

Pilot bounded_pilot(core::Network& network, const core::RunOptions& options,
                    double budget_seconds) {
  Pilot pilot{options, false};
  constexpr long kProbeSteps = 2000;
  core::RunOptions probe = options;
  probe.duration = std::min(options.duration, kProbeSteps * options.dt);
  const core::RunResult r = core::simulate(network, probe);
  if (r.steps <= 0 || r.instability || probe.duration >= options.duration) return pilot;
  const double per_step = r.wall_seconds / static_cast<double>(r.steps);
  // sample_states walks the run twice and prices each step's regime: about 3 runs' cost.
  const double affordable_steps = budget_seconds / (3.0 * std::max(per_step, 1e-9));
  const double affordable = affordable_steps * options.dt;
  if (affordable >= options.duration) return pilot;
  pilot.options.duration = std::max(probe.duration, round_down_125(affordable));
  pilot.truncated = pilot.options.duration < options.duration;
  return pilot;
}

}  // namespace stiction::app
