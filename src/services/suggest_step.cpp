#include "services/suggest_step.hpp"

#include <cmath>
#include <algorithm>
#include <cstdio>
#include <limits>
#include <optional>

#include "services/accuracy.hpp"
#include "services/pilot.hpp"
#include "services/run_comparison.hpp"
#include "core/integrator_traits.hpp"
#include "core/simulation.hpp"
#include "sys/interrupt.hpp"

namespace stiction::services {
namespace {

std::string format(const char* pattern, double a, double b = 0.0) {
  char text[200];
  std::snprintf(text, sizeof text, pattern, a, b);
  return text;
}

// Thrown from the progress callback to end a trial that has used up the work budget.
struct TrialTimeout {
  double reached = 0.0;
};

// Halvings of a candidate after failed trials: a stick inside a short impact can need a step
// several hundred times below the stability limit (two glancing spheres: 1.5e-6 s against
// 7e-4 s), and the trials' work budget bounds the cost anyway.
constexpr int kMaxHalvings = 11;

// The work the trials have done, in component-steps (steps times the scene's components), as
// the pilot run is bounded (pilot.hpp): counted, not timed, so that the same scene gets the
// same verdict and the same advice on every machine, instrumented builds included.
struct TrialWork {
  double limit = 0.0;
  double spent = 0.0;
  double components = 1.0;
  bool exhausted() const { return spent >= limit; }
};

// A run of the scene at `options`, ended by TrialTimeout once the work budget is used up (the
// progress ticks come at fixed step counts, so where it ends does not depend on the machine).
core::RunResult counted_run(scene::Scene& scene, const core::RunOptions& options,
                            TrialWork& work) {
  const double duration = options.duration;
  const double steps = std::ceil(duration / options.dt);
  const auto callback = [&](double fraction) {
    if (sys::interrupted()) throw sys::Interrupted{};
    if (work.spent + fraction * steps * work.components > work.limit) {
      work.spent = work.limit;
      throw TrialTimeout{fraction * duration};
    }
  };
  core::RunResult r = core::simulate(*scene.network, options, callback);
  work.spent += static_cast<double>(r.steps) * work.components;
  return r;
}

// Why a trial is not accurate against the reference at half its step, by the one
// comparison of two runs that `run` judges a run by (run_comparison.hpp); `excess`, the
// largest ratio of a judged quantity's estimated error to its tolerance (infinity for a
// missing event), tells whether halving the step brings it closer.
struct Inaccuracy {
  std::string reason;
  double excess = 0.0;
};

std::optional<Inaccuracy> trial_inaccurate(const scene::Scene& scene, const JudgeRule& rule,
                                           const core::RunOptions& trial_options,
                                           const core::RunResult& trial,
                                           const core::RunResult& reference) {
  const MotionScales scales(reference.trajectory);
  ComparisonSetup setup = companion_setup(trial_options, rule);
  setup.scales = &scales;
  const RunComparison c = compare_runs(*scene.network, trial, reference, setup);
  if (c.accurate()) return std::nullopt;
  Inaccuracy in{c.reasons.front(), 0.0};
  for (const auto* list : {&c.events, &c.finals}) {
    for (const ComparedQuantity& q : *list) {
      if (!q.judged || q.within()) continue;
      const double r = q.error && q.tolerance > 0.0 ? *q.error / q.tolerance
                                                    : std::numeric_limits<double>::infinity();
      in.excess = std::max(in.excess, r);
    }
  }
  return in;
}


// Confirms `candidate` for a run at `base` (its integrator and duration), halving it after
// each failed trial; `origin` says where the candidate came from.
StepSuggestion confirm_step(scene::Scene& scene, const core::RunOptions& base, double candidate,
                            const std::string& origin, TrialWork& work,
                            bool pilot_bounded, int trials = kMaxHalvings + 1) {
  StepSuggestion s;
  s.dt = candidate;
  const auto halvings = [](int n) {
    return n == 0 ? std::string() : format(", halved %g time(s) after failed trials", n);
  };
  // The scene's [accuracy] rule, read once for all the trials (run has validated it).
  const JudgeRule rule = read_judge_rule(scene);
  std::string last_failure;
  double previous_excess = 0.0;
  int stalled = 0;
  for (int trial = 0; trial < trials; ++trial) {
    if (work.exhausted()) break;
    core::RunOptions options = base;
    options.dt = s.dt;
    // Each trial is bounded (issue 25): a scene of 1e305 s at the candidate would be
    // refused by the run limits or never end, so past kMaxTrialSteps the trial covers only
    // what a pilot run may.
    constexpr double kMaxTrialSteps = 1e7;
    if (pilot_bounded || !(options.duration / options.dt <= kMaxTrialSteps)) {
      options = bounded_pilot(*scene.network, options).options;
    }
    // Trials stop on SIGINT/SIGTERM, whichever command asked for them (the caller's run
    // options may not have the flag yet: the guard runs before the simulation).
    options.stop = &sys::interrupt_flag();
    const core::RunOptions reference_options = companion_options(options);
    try {
      const core::RunResult r = counted_run(scene, options, work);
      if (r.interrupted) throw sys::Interrupted{};
      if (r.instability) {
        last_failure = format("unstable at t = %.3g s", r.instability->time);
        s.dt /= 2.0;
        continue;
      }
      const core::RunResult ref = counted_run(scene, reference_options, work);
      if (ref.interrupted) throw sys::Interrupted{};
      if (ref.instability) {
        last_failure = format("the reference at half the step went unstable at t = %.3g s",
                              ref.instability->time);
        s.dt /= 2.0;
        continue;
      }
      if (const auto differ = trial_inaccurate(scene, rule, options, r, ref)) {
        last_failure = differ->reason;
        // A quantity that does not converge (a bounce's phase, a count of micro-bounces the
        // rule judges) is not fixed by a smaller step: after two halvings that did not bring
        // the worst error 1.5x closer to its tolerance each, stop saying so.
        stalled = previous_excess > 0.0 && !(differ->excess * 1.5 < previous_excess)
                      ? stalled + 1
                      : 0;
        previous_excess = differ->excess;
        if (stalled >= 2) {
          s.failure = last_failure;
          s.how = origin + halvings(trial) +
                  "; not confirmed: the trials' error does not shrink with the step (" +
                  last_failure + ")";
          return s;
        }
        s.dt /= 2.0;
        continue;
      }
      s.verified = true;
      s.how = origin + halvings(trial) +
              format(
                  "; a trial at this step ran %g s of the scene and was accurate against a run "
                  "at half the step (docs/accuracy.md)",
                  options.duration);
      return s;
    } catch (const TrialTimeout& t) {
      s.how = origin + halvings(trial) +
              format(
                  "; not confirmed: the trials reached t = %.3g s of %g s within their work "
                  "budget",
                  t.reached, options.duration);
      return s;
    }
  }
  s.failure = last_failure;
  s.how = origin + halvings(trials) + "; not confirmed" +
          (last_failure.empty() ? std::string(" (interrupted or out of time)")
                                : ": the last trial failed (" + last_failure + ")");
  return s;
}

// Where the predicted candidate comes from, for the explanation.
std::string predicted_origin(const StepCheck& check) {
  if (check.chatter_limit <= 0.0 || (!check.unbounded && check.instability_limit <= 0.0)) {
    return format("0.8 x the smallest step analysed, %.3g s", check.lowest_step);
  }
  if (check.chatter_limit < check.instability_limit ||
      (check.unbounded && check.chatter_limit < kMaxAnalysedStep)) {
    return format("0.8 x the predicted step %.3g s above which stuck friction chatters",
                  check.chatter_limit);
  }
  return format("0.8 x the predicted instability limit %.3g s", check.instability_limit);
}

TrialWork work_budget(const scene::Scene& scene, double component_steps) {
  const core::Network& n = *scene.network;
  return {component_steps, 0.0,
          std::max(1.0, static_cast<double>(n.admittances().size() + n.impedances().size()))};
}

}  // namespace

StepSuggestion suggest_step(scene::Scene& scene, const StepCheck& check, double trial_work,
                            bool pilot_bounded) {
  const core::RunOptions failed = scene.run;
  if (core::is_adaptive(failed.integrator)) {
    return {failed.dt / 4.0, false, "lower the tolerance instead", ""};
  }
  TrialWork work = work_budget(scene, trial_work);
  const double predicted = check.safe_step();
  if (check.applies && !check.skipped && predicted < failed.dt) {
    return confirm_step(scene, failed, predicted, predicted_origin(check), work, pilot_bounded);
  }
  return confirm_step(scene, failed, failed.dt / 4.0,
                      "a quarter of the failed step (the prediction sees no limit below it)",
                      work, pilot_bounded);
}

StepSuggestion trial_at_step(scene::Scene& scene, double trial_work) {
  TrialWork work = work_budget(scene, trial_work);
  StepSuggestion s = confirm_step(scene, scene.run, scene.run.dt, "the step itself", work, true, 1);
  s.dt = scene.run.dt;  // a failed trial halved it: the answer is about this step
  if (s.verified) {
    s.how = "it ran stable and accurate against a run at half the step (docs/accuracy.md)";
  } else if (!s.failure.empty()) {
    s.how = "it failed: " + s.failure;
  } else {
    s.how = format("not finished within its work budget of %.3g component-steps", trial_work);
  }
  return s;
}

StepSuggestion recommend_step(scene::Scene& scene, const StepCheck& check, double trial_work) {
  core::RunOptions base = scene.run;
  base.integrator = check.integrator;
  TrialWork work = work_budget(scene, trial_work);
  const bool limited = !check.unbounded || check.chatter_limit < kMaxAnalysedStep;
  StepSuggestion s =
      limited ? confirm_step(scene, base, check.safe_step(), predicted_origin(check), work, true)
              : confirm_step(scene, base, scene.run.dt,
                             "the scene's step (no limit predicted up to 1 s)", work, true);
  if (!s.verified) return s;
  // The prediction is linear and its chatter limit conservative (a stuck contact that
  // chatters in the linearization may still stick on time): grow the confirmed step by
  // kGrowth while trials confirm it, so the advice is not several times below a step that
  // works. Stopping at the first failure keeps the answer at most 1 / kGrowth = 0.8 of a
  // step that failed.
  constexpr double kGrowth = 1.25;
  constexpr int kGrowthTrials = 6;
  int grown = 0;
  for (; grown < kGrowthTrials; ++grown) {
    if (work.exhausted()) break;
    const StepSuggestion bigger = confirm_step(scene, base, s.dt * kGrowth, "", work, true, 1);
    if (!bigger.verified) break;
    s.dt = bigger.dt;
  }
  if (grown > 0) {
    s.how += format("; grown %g time(s) by 1.25 while trials at the larger step confirmed it",
                    grown);
  }
  return s;
}

}  // namespace stiction::services
