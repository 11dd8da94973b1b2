#include "app/suggest_step.hpp"

#include <chrono>
#include <cstdio>

#include "app/pilot.hpp"
#include "core/stability.hpp"

namespace stiction::app {
namespace {

std::string format(const char* pattern, double a, double b = 0.0) {
  char text[160];
  std::snprintf(text, sizeof text, pattern, a, b);
  return text;
}

// Thrown from the progress callback to end a trial that has used up its time.
struct TrialTimeout {
  double reached = 0.0;
};

// The linearized candidate: 0.8 times the predicted limit when it lies below the failed
// step, else a quarter of the failed step.
StepSuggestion predicted_candidate(scene::Scene& scene) {
  const core::RunOptions& run = scene.run;
  core::RunOptions pilot_options = run;
  pilot_options.dt = run.dt / 4.0;
  const Pilot pilot = bounded_pilot(*scene.network, pilot_options);
  const auto states = core::sample_states(*scene.network, pilot.options, 10);
  const core::StepLimit limit =
      core::predict_step_limit(*scene.network, run.integrator, states, 1e-9, run.dt);
  if (!limit.unbounded && limit.max_step > 0.0 && 0.8 * limit.max_step < run.dt) {
    return {0.8 * limit.max_step, false,
            format("0.8 x the largest stable step %.3g s predicted by linearizing the step map",
                   limit.max_step)};
  }
  return {run.dt / 4.0, false,
          "a quarter of the failed step (the linearization sees no limit below it)"};
}

}  // namespace

StepSuggestion suggest_step(scene::Scene& scene, double trial_budget_seconds) {
  const core::RunOptions failed = scene.run;
  if (failed.integrator == "rk4_adaptive") {
    return {failed.dt / 4.0, false, "lower the tolerance instead"};
  }
  StepSuggestion s = predicted_candidate(scene);
  const std::string origin = s.how;
  const auto start = std::chrono::steady_clock::now();
  const auto halvings = [](int n) {
    return n == 0 ? std::string() : format(", halved %g time(s) after unstable trial runs", n);
  };
  constexpr int kTrials = 6;
  for (int trial = 0; trial < kTrials; ++trial) {
    core::RunOptions options = failed;
    options.dt = s.dt;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double left = trial_budget_seconds - elapsed;
    const double duration = options.duration;
    const auto callback = [&](double fraction) {
      const double used =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (used > trial_budget_seconds) throw TrialTimeout{fraction * duration};
    };
    if (left <= 0.0) break;
    try {
      const core::RunResult r = core::simulate(*scene.network, options, callback);
      if (!r.instability) {
        s.verified = true;
        s.how = origin + halvings(trial) +
                format("; a trial run at this step ran the scene to its end (t = %g s)", duration);
        return s;
      }
      s.dt /= 2.0;  // unstable: the prediction missed a non-linear effect
    } catch (const TrialTimeout& t) {
      s.how = origin + halvings(trial) +
              format(
                  "; not confirmed: a trial run reached t = %.3g s of %g s stable within its "
                  "time budget",
                  t.reached, duration);
      return s;
    }
  }
  s.how =
      origin + format("; not confirmed: trial runs were still unstable down to %.3g s", s.dt * 2.0);
  return s;
}

}  // namespace stiction::app
