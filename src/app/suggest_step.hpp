// The step an instability message suggests, checked before it is suggested: a step that is
// offered must run the same scene to its end. A candidate comes from linearizing the step
// map along a pilot run (0.8 times the predicted limit, core/stability.hpp) or, when the
// linearization sees no limit below the failed step, a quarter of it; then a trial run of
// the whole scene at the candidate decides. A trial that goes unstable halves the
// candidate and tries again. A trial that outlasts its wall-clock budget leaves the
// candidate suggested on the prediction alone, and the explanation says so.
#pragma once

#include <string>

#include "scene/scene.hpp"

namespace stiction::app {

struct StepSuggestion {
  double dt = 0.0;
  bool verified = false;  // a trial at dt ran the scene to its end
  std::string how;        // one clause for the message: how dt was obtained
};

// For scene.run as it failed (integrator and dt). rk4_adaptive: dt is a quarter of the
// first step and `how` says to lower the tolerance instead (no trial).
StepSuggestion suggest_step(scene::Scene& scene, double trial_budget_seconds = 30.0);

}  // namespace stiction::app
