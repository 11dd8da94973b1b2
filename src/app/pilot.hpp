// The pilot run that `check` and the instability hint linearize along (core::sample_states)
// walks the whole scene twice; on a long or expensive scene that takes minutes. A pilot is
// therefore cut to a wall-clock budget: a short probe measures the cost of a step and the
// pilot covers only the first part of the run that fits, rounded down to 1, 2 or 5 times a
// power of ten seconds so that small timing noise does not change the result.
#pragma once

#include "core/network.hpp"
#include "core/simulation.hpp"

namespace stiction::app {

struct Pilot {
  core::RunOptions options;  // the scene's, with the duration cut to the budget
  bool truncated = false;    // options.duration < the scene's duration
};

// `budget_seconds` bounds the two passes of core::sample_states together.
Pilot bounded_pilot(core::Network& network, const core::RunOptions& options,
                    double budget_seconds = 1.5);

// 1, 2 or 5 times a power of ten, at most `x` (x > 0).
double round_down_125(double x);

}  // namespace stiction::app
