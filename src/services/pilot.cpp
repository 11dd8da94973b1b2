#include "services/pilot.hpp"

#include <algorithm>
#include <cmath>

#include "sys/interrupt.hpp"

namespace stiction::services {

Pilot bounded_pilot(core::Network& network, const core::RunOptions& run) {
  // A step of the sampling walk costs roughly a few microseconds per component (measured:
  // ~10 us for both walks of a four-component scene), so this budget is one to three seconds
  // on this project's machine. Counted in steps, not seconds, so that `check` prints the
  // same on every machine.
  constexpr double kComponentSteps = 8e5;
  constexpr double kMinSteps = 1000;
  const double components =
      static_cast<double>(network.admittances().size() + network.impedances().size());
  const double max_steps = std::max(kMinSteps, kComponentSteps / std::max(1.0, components));
  Pilot pilot{run, false};
  pilot.options.stop = &sys::interrupt_flag();  // the sampling walk stops on a signal
  if (run.duration / run.dt > max_steps) {
    pilot.options.duration = max_steps * run.dt;
    pilot.shortened = true;
  }
  return pilot;
}

}  // namespace stiction::services
