// The step `stiction` suggests (after an instability, when the step guard refuses a step,
// and as `check`'s recommendation), checked before it is suggested: a step that is offered
// must run the scene and give the events a finer step gives.
//
// The candidate is 0.8 times the smaller of the predicted limits (app/step_check.hpp), so it
// lies below the step where stuck friction chatters, not only below the instability; when
// the prediction sees no limit below the failed step, a quarter of that. Then a trial run at
// the candidate and a reference at half of it decide: the candidate is confirmed when the
// trial ends without instability and is accurate against the reference by the one
// comparison of two runs that `run`'s accuracy verdict uses (run_comparison.hpp, with the
// scene's [accuracy] rule). A trial that fails halves the candidate and tries again. Trials
// that outlast their work budget leave the candidate suggested on the prediction alone, and
// the explanation says so. The budget is work, not time: component-steps (steps times the
// scene's admittances and impedances, as the pilot run is bounded), so that a scene gets the
// same verdict and the same advice on every machine and in every build.
#pragma once

#include <string>

#include "services/step_check.hpp"
#include "scene/scene.hpp"

namespace stiction::services {

struct StepSuggestion {
  double dt = 0.0;
  bool verified = false;  // a trial at dt ran and matched the reference at dt / 2
  std::string how;        // one clause for the message: how dt was obtained
  std::string failure;    // what the last failed trial found (empty: none failed)
};

// For scene.run as it failed or was refused (integrator and dt), with its step check.
// Throws sys::Interrupted when a signal stops a trial.
// rk4_adaptive: dt is a quarter of the first step and `how` says to lower the tolerance
// instead (no trial). With `pilot_bounded` the trials cover only what a pilot run may
// (app/pilot.hpp), as `check` needs.
// What a suggestion's trials may do in all, in component-steps: a simple scene steps about 5e6
// component-steps a second in Release on this project's machine, so 1.5e8 is about 30 s there.
inline constexpr double kSuggestionWork = 1.5e8;
// What the guard's trial of the step itself and check's recommendation may do (about 10 s).
inline constexpr double kTrialWork = 5e7;

StepSuggestion suggest_step(scene::Scene& scene, const StepCheck& check,
                            double trial_work = kSuggestionWork, bool pilot_bounded = false);

// One trial of scene.run's own step, as a pilot run is bounded, against a reference at half
// the step: `verified` when it ran stable and accurate. The step guard asks this before it
// refuses a step above the predicted limit (the prediction is linear; contacts that open and
// close can make it conservative).
StepSuggestion trial_at_step(scene::Scene& scene, double trial_work = kTrialWork);

// `check`'s recommendation for check.integrator: the same candidate and confirmation, with
// the trials bounded as a pilot run is; then the confirmed step grows by 1.25 while trials
// at the larger step confirm it (the linear prediction, its chatter limit above all, can be
// several times below a step that works), stopping at the first failure.
StepSuggestion recommend_step(scene::Scene& scene, const StepCheck& check,
                              double trial_work = kTrialWork);

}  // namespace stiction::services
