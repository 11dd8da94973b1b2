#include "services/step_guard.hpp"

#include <algorithm>
#include <cstdio>

namespace stiction::services {

StepGuard guard_step(scene::Scene& scene, bool force, double suggestion_work,
                     SharedStepChecks* shared, std::size_t point) {
  StepGuard guard;
  guard.check = shared != nullptr ? shared->check(scene, point) : check_step(scene);
  const std::string verdict = guard.check.verdict();
  if (verdict == "unstable") {
    if (force) {
      guard.check.forced = true;
      guard.warning = step_check_text(guard.check) + "; run anyway (--force-step)";
    } else if (const StepSuggestion trial = trial_at_step(scene, std::min(kTrialWork, suggestion_work));
               trial.verified) {
      // The linear prediction was conservative here: a trial of this very step ran stable
      // and accurate, so the step is not refused (and the run's own monitors stay on).
      guard.check.trial_confirmed = true;
      guard.check.trial = trial.how;
    } else {
      guard.check.trial = trial.how;
      guard.refusal = suggest_step(scene, guard.check, suggestion_work);
    }
  } else if (verdict == "chatter") {
    // The chatter limit is a linear prediction too: a trial of this step decides whether
    // the warning is right (a stuck element that chatters in the linearization may still
    // stick on time).
    const StepSuggestion trial = trial_at_step(scene, std::min(kTrialWork, suggestion_work));
    guard.check.trial = trial.how;
    if (trial.verified) {
      guard.check.trial_confirmed = true;
    } else {
      char below[120];
      std::snprintf(below, sizeof below, "; steps below %.3g s avoid it",
                    guard.check.safe_step());
      guard.warning = step_check_text(guard.check) + below + "; a trial at this step: " +
                      trial.how;
    }
  } else if (guard.check.skipped) {
    guard.warning = step_check_text(guard.check);
  }
  return guard;
}

scene::Warning step_warning(const scene::Scene& scene, bool dt_from_command_line,
                            const std::string& text) {
  scene::Warning w;
  w.file = scene.path.string();
  w.key = "simulation.dt";
  if (dt_from_command_line) {
    w.file = "(command line)";
    w.key = "--dt";
  } else if (const toml::node* dt = scene.document.at_path("simulation.dt").node()) {
    const toml::source_region& where = dt->source();
    if (where.path) w.file = *where.path;
    w.line = static_cast<long>(where.begin.line);
    w.column = static_cast<long>(where.begin.column);
  }
  w.text = w.key + ": " + text;
  return w;
}

nlohmann::ordered_json warnings_json(const std::vector<scene::Warning>& warnings) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const scene::Warning& w : warnings) {
    list.push_back({{"file", w.file},
                    {"line", w.line},
                    {"column", w.column},
                    {"key", w.key},
                    {"text", w.text}});
  }
  return list;
}

void print_refusal(const std::string& scene_name, const StepGuard& guard) {
  // "works" only for a step a trial confirmed; otherwise it is a step to try.
  std::fprintf(stderr, "error: %s: %s; nothing was simulated.\n", scene_name.c_str(),
               step_check_text(guard.check).c_str());
  if (!guard.check.trial.empty()) {
    std::fprintf(stderr, "  a trial at dt = %g s: %s\n", guard.check.dt,
                 guard.check.trial.c_str());
  }
  std::fprintf(stderr, "  %s: --dt %g (%s)\n  --force-step runs it anyway\n",
               guard.refusal->verified ? "a step that works" : "a smaller step to try",
               guard.refusal->dt, guard.refusal->how.c_str());
}

}  // namespace stiction::services
