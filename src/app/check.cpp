#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "services/network_graph.hpp"
#include "services/pilot.hpp"
#include "services/step_check.hpp"
#include "services/step_guard.hpp"
#include "services/suggest_step.hpp"
#include "services/verify_settings.hpp"
#include "core/integrator.hpp"
#include "core/stability.hpp"
#include "plot/plot_spec.hpp"
#include "render/render_settings.hpp"
#include "scene/scene.hpp"
#include "scene/toml_reader.hpp"
#include "sys/interrupt.hpp"

namespace stiction::app {
using namespace services;
namespace {

// Mobility (inverse effective mass or inertia) that impedance i sees at the initial state:
// push with a unit force through its map, let the admittances accelerate for a unit time
// and read the velocity part of x_hat back. The largest entry gives the stiffest mode, the
// one that limits the step. Works for every map whose x_hat is [position (n), velocity (n)]
// with n = force size; NaN otherwise.
double largest_mobility(core::Network& network, int i) {
  const core::CoordinateMap& map = network.map_of(i);
  const int n = map.force_size();
  if (map.motion_size() != 2 * n) return std::nan("");
  const core::Vec x0 = network.initial_state();
  core::Vec base_hat(map.motion_size()), pushed_hat(map.motion_size());
  map.motion(x0, base_hat);
  double largest = 0.0;
  for (int k = 0; k < n; ++k) {
    core::Vec u = core::Vec::Zero(n);
    u[k] = 1.0;
    core::Vec u_hat = core::Vec::Zero(network.input_dim());
    map.apply(x0, u, u_hat);
    core::Vec x1 = x0;
    for (std::size_t a = 0; a < network.admittances().size(); ++a) {
      const core::Admittance& adm = *network.admittances()[a];
      const core::Slot s = network.admittance_slot(static_cast<int>(a));
      core::Vec with(s.state_size), without(s.state_size);
      adm.derivative(x0.segment(s.state_offset, s.state_size),
                     u_hat.segment(s.input_offset, s.input_size), with);
      adm.derivative(x0.segment(s.state_offset, s.state_size), core::Vec::Zero(s.input_size),
                     without);
      x1.segment(s.state_offset, s.state_size) += with - without;
    }
    map.motion(x1, pushed_hat);
    // The moving side receives -u: a positive mobility shows as a negative response.
    largest = std::max(largest, -(pushed_hat[n + k] - base_hat[n + k]));
  }
  return largest;
}

std::string labels_of(const core::LayoutEntry& entry) {
  std::string out;
  for (const auto& l : entry.labels) out += (out.empty() ? "" : " ") + l;
  return out;
}

}  // namespace

namespace {

struct StiffElement {
  std::string component, type;
  double stiffness = 0.0, mobility = 0.0, omega = 0.0, damping_ratio = 0.0;
  bool wired = false;  // an effective mass could be computed
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
  render::RenderSettings render;
  std::vector<std::string> plots;
  VerifySettings verify;
};

// "FILE:LINE:COL: error: MESSAGE" split for machines; other messages are kept whole.
nlohmann::json error_json(const std::string& message) {
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
  return e;
}

nlohmann::json number_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json();
}

// A fixed-step integrator's figures, each named for what it is: the step above which a run
// blows up, and the (smaller) step above which stuck friction chatters but stays bounded.
void print_limit(const IntegratorLimit& l, const core::RunOptions& run) {
  const char* name = l.integrator.c_str();
  if (l.limit.unbounded) {
    std::printf("  %-17s stable at every step up to 1 s\n", name);
    return;
  }
  if (l.limit.max_step <= 0.0) {
    std::printf("  %-17s unstable at every step size tried\n", name);
    return;
  }
  std::printf("  %-17s unstable above %.3g s (limiting state at t = %.3g s)", name,
              l.limit.max_step, l.limit.limiting_time);
  if (l.integrator == run.integrator) {
    std::printf("; scene dt %g s: %s", run.dt, run.dt < l.limit.max_step ? "ok" : "TOO LARGE");
  }
  std::printf("\n");
  if (l.limit.chatter_free_step < l.limit.max_step) {
    std::printf(
        "  %-17s stuck friction chatters above %.3g s (bounded by its limit force, not "
        "an instability)\n",
        "", l.limit.chatter_free_step);
  }
  std::printf("  %-17s recommended: --dt %.3g (%s)\n", "", l.recommended.dt,
              l.recommended.how.c_str());
}

void print_text(const scene::Scene& scene, const CheckReport& report) {
  const core::Network& network = *scene.network;
  const core::RunOptions& run = scene.run;
  std::printf("%s: ok (%s)\n", scene.name.c_str(), scene.path.c_str());
  if (!scene.description.empty()) std::printf("  %s\n", scene.description.c_str());
  for (const scene::Warning& w : scene.warnings) std::printf("%s\n", scene::format_warning(w).c_str());
  std::printf("simulation: %s, dt = %g s, duration = %g s, %g rows/s\n", run.integrator.c_str(),
              run.dt, run.duration, run.output_rate);
  std::printf("render: %dx%d at %g fps; plots: %zu; verify: %s\n", report.render.width,
              report.render.height, report.render.fps, report.plots.size(),
              report.verify.at.empty()
                  ? "first frame, each event, last frame"
                  : (std::to_string(report.verify.at.size()) + " frame times").c_str());

  std::printf("\nstate layout (%d numbers):\n", network.state_dim());
  for (const core::LayoutEntry& e : network.layout()) {
    if (e.size == 0) {
      std::printf("  %-9s %s (%s): no state\n", "-", e.component.c_str(), e.type.c_str());
      continue;
    }
    std::string range = "[";  // appended piecewise: GCC 12 -Wrestrict false positive
    range += std::to_string(e.offset) + ".." + std::to_string(e.offset + e.size - 1) + "]";
    std::printf("  %-9s %s (%s): %s\n", range.c_str(), e.component.c_str(), e.type.c_str(),
                labels_of(e).c_str());
  }

  std::printf(
      "\nstiffest elements, each alone against its effective mass (linearized at the "
      "initial state; the whole network's limits are below):\n");
  for (const StiffElement& s : report.stiff) {
    if (!s.wired) {
      std::printf("  %s (%s): K = %g; no effective mass could be computed for its wiring\n",
                  s.component.c_str(), s.type.c_str(), s.stiffness);
      continue;
    }
    std::printf(
        "  %s (%s): K = %g against an effective mass/inertia %g: omega = %.5g rad/s, "
        "damping ratio %.3g; alone, this undamped mode would make rk4 unstable above "
        "2.83 / omega = %.3g s\n",
        s.component.c_str(), s.type.c_str(), s.stiffness, 1.0 / s.mobility, s.omega,
        s.damping_ratio, 2.8284271247461903 / s.omega);
  }
  if (report.stiff.empty()) std::printf("  no stiff elements\n");

  std::printf("\npredicted step limits of the whole network (step map linearized at up to %d "
              "states of each regime of a pilot run at the scene's settings (at most %zu in all)",
              kStatesPerRegime, core::kMaxSampledStates);
  if (report.pilot.shortened) {
    std::printf(" over its first %g s of %g s, the part that fits its step budget (docs/limits.md)",
                report.pilot.options.duration, run.duration);
  }
  std::printf("; a mode growing > 5%% per step counts as unstable):\n");
  for (const IntegratorLimit& l : report.limits) print_limit(l, run);
}

nlohmann::json report_json(const scene::Scene& scene, const CheckReport& report) {
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

int check_scene(const std::string& scene_name, const std::string& graph_path, bool json) {
  scene::Scene scene = scene::load_scene(scene_name);
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

  for (std::size_t i = 0; i < network.impedances().size(); ++i) {
    const core::Impedance& imp = *network.impedances()[i];
    const core::StiffnessHint* hint = network.capabilities(static_cast<int>(i)).stiffness;
    if (hint == nullptr) continue;
    StiffElement s;
    s.stiffness = hint->stiffness();
    if (!(s.stiffness > 0.0)) continue;
    s.component = imp.name();
    s.type = std::string(imp.type());
    s.mobility = largest_mobility(network, static_cast<int>(i));
    s.wired = s.mobility > 0.0;
    if (s.wired) {
      s.omega = std::sqrt(s.stiffness * s.mobility);
      const double B = hint->damping();
      s.damping_ratio = std::isfinite(B) ? B * s.mobility / (2.0 * s.omega) : std::nan("");
    }
    report.stiff.push_back(s);
  }

  // The real limit depends on all elements at once, on the friction laws' stage sizes and on
  // the states the scene passes through: linearize the actual step map along a run.
  report.pilot = bounded_pilot(network, run);
  const auto states = core::sample_states(network, report.pilot.options, kStatesPerRegime);
  if (sys::interrupted()) throw sys::Interrupted{};
  constexpr double kLowestStep = 1e-9;
  for (const std::string name : {"euler", "symplectic_euler", "heun", "rk4"}) {
    const core::StepLimit limit = core::predict_step_limit(network, name, states, kLowestStep);
    const StepCheck as_check = step_check_from(limit, name, run.dt, kLowestStep);
    report.limits.push_back({name, limit, recommend_step(scene, as_check)});
    if (sys::interrupted()) throw sys::Interrupted{};
  }

  if (json) {
    std::printf("%s\n", report_json(scene, report).dump(2).c_str());
  } else {
    print_text(scene, report);
  }
  if (!graph_path.empty()) {
    write_network_dot(scene, graph_path);
    if (!json) std::printf("\nwrote %s\n", graph_path.c_str());
  }
  return kExitOk;
}

}  // namespace

int check_command(const std::string& scene_name, const std::string& graph_path, bool json) {
  if (!json) return check_scene(scene_name, graph_path, false);
  try {
    return check_scene(scene_name, graph_path, true);
  } catch (const scene::InputError& e) {
    // Machines read stdout; people still see the located message on stderr.
    nlohmann::json j{{"ok", false}, {"errors", nlohmann::json::array({error_json(e.what())})}};
    std::printf("%s\n", j.dump(2).c_str());
    std::fprintf(stderr, "%s\n", e.what());
    return kExitBadInput;
  }
}

int scenes_command() {
  const auto scenes = scene::bundled_scenes();
  std::size_t width = 0;
  for (const auto& [name, description] : scenes) width = std::max(width, name.size());
  for (const auto& [name, description] : scenes) {
    std::printf("%-*s  %s\n", static_cast<int>(width), name.c_str(), description.c_str());
  }
  return kExitOk;
}

}  // namespace stiction::app
