#include "services/check_report.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <regex>

#include "core/integrator.hpp"
#include "services/dynamics_fingerprint.hpp"
#include "services/run_comparison.hpp"
#include "services/step_check.hpp"
#include "services/step_guard.hpp"
#include "sys/interrupt.hpp"

namespace stiction::services {
namespace {

nlohmann::json number_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json();
}

}  // namespace

const std::vector<std::string>& checked_integrators() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> analysed;
    for (const core::IntegratorTraits& t : core::integrator_table()) {
      if (t.step_analysed()) analysed.push_back(t.name);
    }
    return analysed;
  }();
  return names;
}

CheckReport check_scene(scene::Scene& scene) {
  core::Network& network = *scene.network;
  const core::RunOptions& run = scene.run;

  // What `run` reads before it simulates, with the same readers, hence the same messages.
  CheckReport report;
  report.render = render::read_render_settings(scene);
  const std::vector<core::ColumnInfo> columns = core::column_infos(network);
  std::vector<plot::PlotSpec> specs =
      plot::read_plot_specs(scene.document, scene.path.string(), columns);
  if (specs.empty()) specs = plot::default_plot_specs(columns);
  for (const plot::PlotSpec& s : specs) report.plots.push_back(s.name);
  report.verify = read_verify_settings(scene.document, run.duration);
  read_judge_rule(scene);  // [accuracy]: the same errors as run

  const core::Vec x0 = network.initial_state();
  double mobility_work = 0.0;
  for (std::size_t i = 0; i < network.impedances().size(); ++i) {
    const core::Impedance& imp = *network.impedances()[i];
    const core::StiffnessHint* hint = network.capabilities(static_cast<int>(i)).stiffness;
    if (hint == nullptr) continue;
    StiffElement s;
    s.stiffness = hint->stiffness();
    if (!(s.stiffness > 0.0)) continue;
    s.component = imp.name();
    s.type = std::string(imp.type());
    if (sys::interrupted()) throw sys::Interrupted{};
    s.over_budget = mobility_work > kMobilityWork;
    s.mobility = s.over_budget ? std::nan("")
                               : largest_mobility(network, static_cast<int>(i), x0, &mobility_work);
    s.wired = s.mobility > 0.0;
    if (s.wired) {
      s.omega = std::sqrt(s.stiffness * s.mobility);
      const double B = hint->damping();
      s.damping_ratio = std::isfinite(B) ? B * s.mobility / (2.0 * s.omega) : std::nan("");
    }
    report.stiff.push_back(s);
  }

  if (sys::interrupted()) throw sys::Interrupted{};
  // Bounded work (issue 25): the dense linearization grows as the cube of the state count.
  if (!core::analysable(network)) {
    report.pilot = {run, false};
    report.analysis_skipped =
        "the network's largest island (bodies its elements couple) has " +
        std::to_string(core::largest_island_states(network)) + " states, more than the " +
        std::to_string(core::kMaxAnalysedStates) +
        " the step analysis linearizes in seconds (docs/limits.md): no step limits predicted, "
        "no step recommended; the single-element figures above are the guide";
    return report;
  }
  // The real limit depends on all elements at once, on the friction laws' stage sizes and on
  // the states the scene passes through: linearize the actual step map along a run.
  report.pilot = bounded_pilot(network, run);
  const auto states = core::sample_states(network, report.pilot.options, kStatesPerRegime);
  if (sys::interrupted()) throw sys::Interrupted{};
  constexpr double kLowestStep = 1e-9;
  // The scene's own integrator first: when the budget runs out, its answer is the one kept.
  std::vector<std::string> order = checked_integrators();
  std::stable_partition(order.begin(), order.end(),
                        [&](const std::string& n) { return n == run.integrator; });
  core::AnalysisBudget budget{kCheckAnalysisWork, 0.0};
  std::map<std::string, IntegratorLimit> found;
  for (const std::string& name : order) {
    IntegratorLimit l{name, {}, {}};
    if (budget.spent > budget.limit) {
      l.limit.over_budget = true;
    } else {
      l.limit = core::predict_step_limit(network, name, states, kLowestStep, 1.0,
                                         &sys::interrupt_flag(), &budget);
      if (sys::interrupted() || (l.limit.interrupted && !l.limit.over_budget))
        throw sys::Interrupted{};
      if (!l.limit.over_budget)
        l.recommended = recommend_step(scene, step_check_from(l.limit, name, run.dt, kLowestStep));
    }
    if (sys::interrupted()) throw sys::Interrupted{};
    found.emplace(name, std::move(l));
  }
  for (const std::string& name : checked_integrators()) report.limits.push_back(found.at(name));
  report.analysis_work = budget.spent;
  return report;
}

nlohmann::json check_json(const scene::Scene& scene, const CheckReport& report) {
  const core::Network& network = *scene.network;
  const core::RunOptions& run = scene.run;
  nlohmann::json j;
  j["ok"] = true;
  j["errors"] = nlohmann::json::array();
  j["warnings"] = nlohmann::json(warnings_json(scene.warnings));
  j["scene"] = scene.name;
  j["path"] = scene.path.string();
  j["simulation"] = {{"integrator", run.integrator},
                     {"dt", run.dt},
                     {"duration", run.duration},
                     {"output_rate", run.output_rate}};
  // Every integrator with its traits (DESIGN section 3): other tools take the names from here.
  nlohmann::json integrators = nlohmann::json::array();
  for (const core::IntegratorTraits& t : core::integrator_table()) {
    integrators.push_back(
        {{"name", t.name}, {"order", t.order}, {"implicit", t.implicit}, {"adaptive", t.adaptive}});
  }
  j["integrators"] = integrators;
  j["state_dim"] = network.state_dim();
  nlohmann::json layout = nlohmann::json::array();
  for (const core::LayoutEntry& e : network.layout()) {
    layout.push_back({{"component", e.component},
                      {"type", e.type},
                      {"offset", e.offset},
                      {"size", e.size},
                      {"labels", e.labels}});
  }
  j["layout"] = layout;
  nlohmann::json stiff = nlohmann::json::array();
  for (const StiffElement& s : report.stiff) {
    nlohmann::json e{{"component", s.component}, {"type", s.type}, {"stiffness", s.stiffness}};
    if (s.over_budget) e["not_computed"] = "bounded work: the elements before took its budget";
    if (s.wired) {
      e["effective_mass"] = 1.0 / s.mobility;
      e["omega"] = s.omega;
      e["damping_ratio"] = number_or_null(s.damping_ratio);
      e["alone_rk4_unstable_above"] = 2.8284271247461903 / s.omega;
    }
    stiff.push_back(e);
  }
  j["stiff_elements"] = stiff;
  j["pilot"] = {{"duration", report.pilot.options.duration}, {"truncated", report.pilot.shortened}};
  nlohmann::json limits = nlohmann::json::object();
  for (const IntegratorLimit& l : report.limits) {
    nlohmann::json e;
    e["analysed"] = !l.limit.over_budget;
    if (l.limit.over_budget) {
      e["reason"] = "not analysed: the step analysis had used its work budget (docs/command_line.md)";
      limits[l.integrator] = e;
      continue;
    }
    e["unbounded"] = l.limit.unbounded;
    e["unstable_above"] = l.limit.unbounded ? nlohmann::json() : nlohmann::json(l.limit.max_step);
    e["limiting_time"] = l.limit.limiting_time;
    e["chatters_above"] = l.limit.chatter_free_step < l.limit.max_step
                              ? nlohmann::json(l.limit.chatter_free_step)
                              : nlohmann::json();
    if (l.integrator == run.integrator)
      e["scene_dt_ok"] = l.limit.unbounded || run.dt < l.limit.max_step;
    e["recommended_step"] = l.recommended.dt;
    e["recommended_confirmed"] = l.recommended.verified;
    e["recommendation"] = l.recommended.how;
    limits[l.integrator] = e;
  }
  j["step_limits"] = limits;
  j["analysis"] = {{"skipped", !report.analysis_skipped.empty()},
                   {"state_dim", network.state_dim()},
                   {"largest_island_states", core::largest_island_states(network)},
                   {"max_states", core::kMaxAnalysedStates},
                   {"work", report.analysis_work},
                   {"work_budget", kCheckAnalysisWork}};
  if (!report.analysis_skipped.empty()) j["analysis"]["reason"] = report.analysis_skipped;
  j["render"] = {{"size", {report.render.width, report.render.height}}, {"fps", report.render.fps}};
  j["plots"] = report.plots;
  j["verify"] = {{"at", report.verify.at},
                 {"pixel_tolerance", report.verify.pixel_tolerance},
                 {"max_differing", report.verify.max_differing},
                 {"max_rms", report.verify.max_rms},
                 {"rel_tolerance", report.verify.rel_tolerance},
                 {"abs_tolerance", report.verify.abs_tolerance}};
  return j;
}

nlohmann::json check_error_json(const std::string& message) {
  static const std::regex located(R"(^(.*):([0-9]+):([0-9]+): error: ([\s\S]*)$)");
  std::smatch m;
  nlohmann::json e;
  if (std::regex_match(message, m, located)) {
    e["file"] = m[1].str();
    e["line"] = std::stol(m[2].str());
    e["column"] = std::stol(m[3].str());
    e["message"] = m[4].str();
  } else {
    e["message"] = message.rfind("error: ", 0) == 0 ? message.substr(7) : message;
  }
  return nlohmann::json{{"ok", false}, {"errors", nlohmann::json::array({e})}};
}

}  // namespace stiction::services
