// The pilot runs that `check` and the step suggestion after an instability linearize along
// (core::sample_states walks the run twice). They are bounded whatever the scene: a duration
// of 3e6 s or a step of 1e-300 must not make `check` run for ever. The bound is a number of
// steps inversely proportional to the number of components (8e5 component-steps, one to three
// seconds here), so that the advice is the same on every machine; the pilot covers only as
// much of the scene's duration as fits.
#pragma once

#include "core/network.hpp"
#include "core/simulation.hpp"

namespace stiction::services {

struct Pilot {
  core::RunOptions options;  // the run to sample, duration possibly shortened
  bool shortened = false;
};

Pilot bounded_pilot(core::Network& network, const core::RunOptions& run);

}  // namespace stiction::services
