// `stiction check SCENE [--json] [--graph FILE]`: prints what services::check_scene finds,
// as text or as JSON (services/check_report.hpp), and `stiction scenes`.
#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "core/islands.hpp"
#include "core/stability.hpp"
#include "scene/scene.hpp"
#include "scene/toml_reader.hpp"
#include "services/check_report.hpp"
#include "services/network_graph.hpp"
#include "services/step_check.hpp"
#include "text/number_text.hpp"

namespace stiction::app {
using namespace services;
namespace {

std::string labels_of(const core::LayoutEntry& entry) {
  std::string out;
  for (const auto& l : entry.labels) out += (out.empty() ? "" : " ") + l;
  return out;
}

// One line of a listing: where (a state range, or empty), which component, and what it says.
struct AlikeLine {
  std::string where, component, text;
};

// The lines, with each run of lines that say the same of different components (1000 spheres,
// each with its floor contact) printed as its first line and one line naming the rest.
void print_alike(const std::vector<AlikeLine>& lines, int where_width) {
  for (std::size_t i = 0; i < lines.size();) {
    std::size_t end = i + 1;
    while (end < lines.size() && lines[end].text == lines[i].text) ++end;
    const AlikeLine& l = lines[i];
    if (where_width > 0) {
      std::printf("  %-*s %s %s\n", where_width, l.where.c_str(), l.component.c_str(),
                  l.text.c_str());
    } else {
      std::printf("  %s %s\n", l.component.c_str(), l.text.c_str());
    }
    const std::size_t more = end - i - 1;
    if (more == 1) {
      std::printf("  %-*s %s: the same\n", where_width, lines[i + 1].where.c_str(),
                  lines[i + 1].component.c_str());
    } else if (more > 1) {
      const AlikeLine& last = lines[end - 1];
      std::printf("  %-*s the same for %zu more, %s%s%s to %s%s%s\n", std::max(where_width, 1), "",
                  more, lines[i + 1].component.c_str(), lines[i + 1].where.empty() ? "" : " ",
                  lines[i + 1].where.c_str(), last.component.c_str(), last.where.empty() ? "" : " ",
                  last.where.c_str());
    }
    i = end;
  }
}

// A fixed-step integrator's figures, each named for what it is: the step above which a run
// blows up, and the (smaller) step above which stuck friction chatters but stays bounded.
void print_limit(const IntegratorLimit& l, const core::RunOptions& run) {
  const char* name = l.integrator.c_str();
  if (l.limit.over_budget) {
    std::printf("  %-17s not analysed: the analysis had used its work budget\n", name);
    return;
  }
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
    std::printf("; scene dt %s s: %s", text::shortest(run.dt).c_str(),
                run.dt < l.limit.max_step ? "ok" : "TOO LARGE");
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
  for (const scene::Warning& w : scene.warnings)
    std::printf("%s\n", scene::format_warning(w).c_str());
  // The scene's own values shortest round-trip (as written), computed ones with stated digits.
  std::printf("simulation: %s, dt = %s s, duration = %s s, %s rows/s\n", run.integrator.c_str(),
              text::shortest(run.dt).c_str(), text::shortest(run.duration).c_str(),
              text::shortest(run.output_rate).c_str());
  std::printf("render: %dx%d at %s fps; plots: %zu; verify: %s\n", report.render.width,
              report.render.height, text::shortest(report.render.fps).c_str(), report.plots.size(),
              report.verify.at.empty()
                  ? "first frame, each event, last frame"
                  : (std::to_string(report.verify.at.size()) + " frame times").c_str());

  std::printf("\nstate layout (%d numbers):\n", network.state_dim());
  std::vector<AlikeLine> layout;
  for (const core::LayoutEntry& e : network.layout()) {
    if (e.size == 0) {
      layout.push_back({"-", e.component, "(" + e.type + "): no state"});
      continue;
    }
    std::string range = "[";  // appended piecewise: GCC 12 -Wrestrict false positive
    range += std::to_string(e.offset) + ".." + std::to_string(e.offset + e.size - 1) + "]";
    layout.push_back({range, e.component, "(" + e.type + "): " + labels_of(e)});
  }
  print_alike(layout, 9);
  const std::vector<core::Island> islands = core::find_islands(network);
  std::size_t largest = 0;
  for (const core::Island& i : islands) largest = std::max(largest, i.states.size());
  std::printf(
      "islands (bodies no element couples, stepped and analysed apart): %zu, the "
      "largest with %zu states\n",
      islands.size(), largest);

  std::printf(
      "\nstiffest elements, each alone against its effective mass (linearized at the "
      "initial state; the whole network's limits are below):\n");
  std::vector<AlikeLine> stiff;
  for (const StiffElement& s : report.stiff) {
    const std::string head = "(" + s.type + "): K = " + text::shortest(s.stiffness);
    if (s.over_budget) {
      stiff.push_back({"", s.component,
                       head + "; its effective mass was not computed (bounded work: the "
                              "elements above took the budget)"});
    } else if (!s.wired) {
      stiff.push_back(
          {"", s.component, head + "; no effective mass could be computed for its wiring"});
    } else {
      char text[256];
      std::snprintf(text, sizeof text,
                    " against an effective mass/inertia %.6g: omega = %.5g rad/s, damping ratio "
                    "%.3g; alone, this undamped mode would make rk4 unstable above 2.83 / omega "
                    "= %.3g s",
                    1.0 / s.mobility, s.omega, s.damping_ratio, 2.8284271247461903 / s.omega);
      stiff.push_back({"", s.component, head + text});
    }
  }
  print_alike(stiff, 0);
  if (report.stiff.empty()) std::printf("  no stiff elements\n");

  if (!report.analysis_skipped.empty()) {
    std::printf("\npredicted step limits of the whole network: skipped: %s\n",
                report.analysis_skipped.c_str());
    return;
  }
  std::printf(
      "\npredicted step limits of the whole network (step map linearized at up to %d "
      "states of each regime of a pilot run at the scene's settings (at most %zu in all)",
      kStatesPerRegime, core::kMaxSampledStates);
  if (report.pilot.shortened) {
    std::printf(
        " over its first %.3g s of %s s, the part that fits its step budget (docs/limits.md)",
        report.pilot.options.duration, text::shortest(run.duration).c_str());
  }
  std::printf("; a mode growing > 5%% per step counts as unstable):\n");
  for (const IntegratorLimit& l : report.limits) print_limit(l, run);
  const auto left = std::count_if(report.limits.begin(), report.limits.end(),
                                  [](const IntegratorLimit& l) { return l.limit.over_budget; });
  if (left > 0) {
    std::printf(
        "  (the step analysis stops at a work budget of %.3g units, about 10 s on 2 cores: %ld "
        "of %zu integrators not analysed, the scene's own first; docs/command_line.md)\n",
        services::kCheckAnalysisWork, static_cast<long>(left), report.limits.size());
  }
}

int check_and_print(const std::string& scene_name, const std::string& graph_path, bool json) {
  scene::Scene scene = scene::load_scene(scene_name);
  const CheckReport report = services::check_scene(scene);
  if (json) {
    std::printf("%s\n", check_json(scene, report).dump(2).c_str());
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
  if (!json) return check_and_print(scene_name, graph_path, false);
  try {
    return check_and_print(scene_name, graph_path, true);
  } catch (const scene::InputError& e) {
    // Machines read stdout; people still see the located message on stderr.
    std::printf("%s\n", check_error_json(e.what()).dump(2).c_str());
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
