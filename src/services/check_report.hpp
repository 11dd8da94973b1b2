// `stiction check` as a function: what the scene's readers say (render, plots, verify), its
// stiffest elements each against its effective mass, and the step limits of the whole network
// per fixed-step integrator, linearized along a pilot run (core::predict_step_limit) with a
// recommended step confirmed by trials. The command prints it as text or JSON; the Python
// module returns the JSON as a dict.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/stability.hpp"
#include "plot/plot_spec.hpp"
#include "render/render_settings.hpp"
#include "scene/scene.hpp"
#include "services/pilot.hpp"
#include "services/suggest_step.hpp"
#include "services/verify_settings.hpp"

namespace stiction::services {

struct StiffElement {
  std::string component, type;
  double stiffness = 0.0, mobility = 0.0, omega = 0.0, damping_ratio = 0.0;
  bool wired = false;  // an effective mass could be computed
  bool over_budget = false;  // not computed: the elements before took kMobilityWork
};

struct IntegratorLimit {
  std::string integrator;
  core::StepLimit limit;
  StepSuggestion recommended;  // below the chatter limit, confirmed by trial runs
};

// Everything check finds; printed as text or as JSON.
struct CheckReport {
  std::vector<StiffElement> stiff;
  Pilot pilot;
  std::vector<IntegratorLimit> limits;
  // Non-empty when the network-wide analysis was skipped (more states than
  // core::kMaxAnalysedStates): why, for the text and the JSON. `limits` is then empty.
  std::string analysis_skipped;
  // The step analysis's work (core::AnalysisBudget units); an integrator left when it passed
  // kCheckAnalysisWork has limit.over_budget set and no answer.
  double analysis_work = 0.0;
  render::RenderSettings render;
  std::vector<std::string> plots;
  VerifySettings verify;
};

// The work check's step analysis may spend over all integrators, in core::AnalysisBudget
// units (the cube of each coupled group's size plus n^2, per radius): about 10 s of this
// machine's (2 cores, 2026) at about 3 ns per unit. The bundled scenes but box_stack (5.9e9)
// need at most 2.4e8 (two_link_penalty); a 20-link arm with joint friction (60 coupled states)
// 3.3e9, a 40-link one about 8 times that. The scene's own integrator is analysed first.
inline constexpr double kCheckAnalysisWork = 3e9;

// The fixed-step integrators check predicts limits for, in the order it prints them.
const std::vector<std::string>& checked_integrators();

// Reads what `run` reads before it simulates (same readers, hence the same errors:
// scene::InputError) and predicts the limits. Throws sys::Interrupted on a signal (polled
// between integrators and after the pilot run). The scene's network is used for trials.
CheckReport check_scene(scene::Scene& scene);

// `stiction check --json`'s document for a scene that loaded.
nlohmann::json check_json(const scene::Scene& scene, const CheckReport& report);

// `stiction check --json`'s document for a scene that did not load: {"ok": false, "errors":
// [{"file", "line", "column", "message"}]} ("FILE:LINE:COL: error: MESSAGE" split for
// machines; another message kept whole).
nlohmann::json check_error_json(const std::string& message);

}  // namespace stiction::services
