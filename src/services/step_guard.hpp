// The step guard as every command that simulates applies it (run, compare, verify, each
// point of a sweep): the step check of services/step_check.hpp, then, above a predicted
// limit, a trial of the step itself (services/suggest_step.hpp: trial_at_step, judged as
// `run` judges a run) before anything is said:
//   unstable, the trial fails, not forced -> a refusal with a confirmed step to suggest
//                                            (exit 3, nothing simulated, nothing written);
//   chatter, the trial fails              -> a warning (stderr unless quiet, summary.json);
//   the trial confirms the step           -> `ok`, step_check.confirmed_by_trial;
//   ok, not_checked                       -> nothing to say.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "services/step_check.hpp"
#include "services/suggest_step.hpp"
#include "scene/plausibility.hpp"
#include "scene/scene.hpp"

namespace stiction::services {

struct StepGuard {
  StepCheck check;
  std::optional<StepSuggestion> refusal;  // set: do not simulate, exit 3
  std::optional<std::string> warning;     // set: the run goes on with this warning
};

// `force`: --force-step. `suggestion_work`: the component-steps the trials of a refusal's
// suggestion may take (suggest_step.hpp; the trial of the step itself takes kTrialWork).
// `shared`: the step checks of a sweep's points, shared among points of the same dynamics;
// `point`: the index of the sweep's point `scene` is.
StepGuard guard_step(scene::Scene& scene, bool force, double suggestion_work = kSuggestionWork,
                     SharedStepChecks* shared = nullptr, std::size_t point = 0);

// The guard's warning located as the scene's warnings are: at [simulation] dt of the scene
// file, or on the command line (file "(command line)", key "--dt") when --dt set the step.
scene::Warning step_warning(const scene::Scene& scene, bool dt_from_command_line,
                            const std::string& text);

// summary.json's and check --json's `warnings`: [{"file", "line", "column", "key", "text"}].
nlohmann::ordered_json warnings_json(const std::vector<scene::Warning>& warnings);

// "error: NAME: dt = ... is above ...; a step that works: --dt X (how); --force-step runs it
// anyway" on stderr.
void print_refusal(const std::string& scene_name, const StepGuard& guard);

}  // namespace stiction::services
