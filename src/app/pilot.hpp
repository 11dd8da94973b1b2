// The pilot runs that `check` and the step suggestion after an instability linearize along
// (core::sample_states walks the run twice). They are bounded in wall time whatever the
// scene: a duration of 3e6 s or a step of 1e-300 must not make `check` run for ever. The
// cost of one step is measured on a short run first, and the pilot covers only as much of
// the scene's duration as fits the budget.
#pragma once

#include "core/network.hpp"
#include "core/simulation.hpp"

namespace stiction::app {

struct Pilot {
  core::RunOptions options;  // the run to sample, duration possibly shortened
  bool shortened = false;
};

// `budget_seconds` for both passes of sample_states together (roughly).
Pilot bounded_pilot(core::Network& network, const core::RunOptions& run, double budget_seconds = 2.0);

}  // namespace stiction::app
