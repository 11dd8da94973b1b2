// `stiction compare SCENE SCENE...`: runs each scene as `run --no-video --no-plots` would
// and overlays them in one figure, OUT/compare.png (default out/compare/). The arm scenes
// get the drift comparison (joint angles and their change after the arm stopped); other
// runs a figure of the signals they have in common, or of the ones --signals names.
// A scene argument may carry overrides of its own after '@' ("sphere_roll@ground.mu=0.3");
// each run is labelled by its scene name plus the overrides that tell it from the others.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "services/run_support.hpp"
#include "services/step_guard.hpp"
#include "core/column_info.hpp"
#include "io/atomic_file.hpp"
#include "plot/plot_spec.hpp"
#include "scene/scene.hpp"
#include "sys/interrupt.hpp"

namespace stiction::app {
using namespace services;
namespace fs = std::filesystem;
namespace {

struct RunRequest {
  std::string scene;                   // name or path
  std::vector<std::string> overrides;  // this run's own, after the shared --set
};

// "path/scene.toml@a.b=1@c=[1, 2]" -> scene and its overrides. An '@' is only a separator
// when the text after it up to the next '@' holds a '=' (so a path may contain '@').
RunRequest parse_request(const std::string& argument) {
  RunRequest request;
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t at = argument.find('@'); at != std::string::npos;
       at = argument.find('@', at + 1)) {
    parts.push_back(argument.substr(start, at - start));
    start = at + 1;
  }
  parts.push_back(argument.substr(start));
  request.scene = parts[0];
  for (std::size_t i = 1; i < parts.size(); ++i) {
    if (parts[i].find('=') == std::string::npos) {
      request.scene += "@" + parts[i];  // part of the path
    } else {
      request.overrides.push_back(parts[i]);
    }
  }
  return request;
}

// Scene name plus the overrides not shared by every run with that scene name; "(run N)" when
// two runs would still read the same.
std::vector<std::string> run_labels(const std::vector<std::string>& names,
                                    const std::vector<RunRequest>& requests) {
  std::vector<std::string> labels;
  for (std::size_t i = 0; i < names.size(); ++i) {
    std::vector<std::string> own;
    for (const std::string& o : requests[i].overrides) {
      bool everywhere = true;
      for (std::size_t j = 0; j < names.size(); ++j) {
        const auto& other = requests[j].overrides;
        if (std::find(other.begin(), other.end(), o) == other.end()) everywhere = false;
      }
      if (!everywhere) own.push_back(o);
    }
    std::string label = names[i];
    if (!own.empty()) {
      label += " (";
      for (std::size_t k = 0; k < own.size(); ++k) label += (k ? ", " : "") + own[k];
      label += ")";
    }
    labels.push_back(label);
  }
  std::map<std::string, int> uses;
  for (const std::string& l : labels) ++uses[l];
  std::map<std::string, int> seen;
  for (std::string& l : labels) {
    if (uses[l] > 1) {
      const std::string base = l;
      l += " (run " + std::to_string(++seen[base]) + ")";
    }
  }
  return labels;
}

}  // namespace

int compare_command(const CompareArguments& args) {
  if (args.scenes.size() < 2) {
    throw scene::InputError("error: compare needs at least two scenes (got " +
                            std::to_string(args.scenes.size()) + ")");
  }
  // Every scene is loaded (and checked) before the first simulation starts.
  std::vector<RunRequest> requests;
  std::vector<scene::Scene> scenes;
  for (const std::string& argument : args.scenes) {
    requests.push_back(parse_request(argument));
    std::vector<std::string> overrides = args.overrides;
    overrides.insert(overrides.end(), requests.back().overrides.begin(),
                     requests.back().overrides.end());
    scenes.push_back(scene::load_scene(requests.back().scene, overrides));
    RunOverrides run;
    run.duration = args.duration;
    apply_overrides(scenes.back(), run);
  }
  std::vector<std::string> names;
  for (const scene::Scene& s : scenes) names.push_back(s.name);
  const std::vector<std::string> labels = run_labels(names, requests);

  // --signals is checked against the scenes' columns before anything runs (exit 2 at once).
  if (!args.signals.empty()) {
    std::vector<core::Trajectory> empty;
    for (const scene::Scene& s : scenes) {
      std::vector<std::string> columns = s.network->signal_columns();
      columns.insert(columns.begin(), "t");
      empty.emplace_back(columns);
    }
    std::vector<plot::Run> probe;
    for (std::size_t i = 0; i < scenes.size(); ++i) probe.push_back({labels[i], &empty[i]});
    plot::comparison_spec(probe, args.signals);
  }

  // The step guard for every run before the first simulation: a refused step ends the
  // comparison with exit 3 and nothing written.
  std::vector<StepCheck> checks;
  for (scene::Scene& s : scenes) {
    const StepGuard guard = guard_step(s, args.force_step);
    if (guard.refusal) {
      print_refusal(s.name, guard);
      return kExitUnstable;
    }
    if (guard.warning && !args.quiet) {
      std::fprintf(stderr, "warning: %s: %s\n", s.name.c_str(), guard.warning->c_str());
    }
    checks.push_back(guard.check);
  }

  const fs::path out = args.out.empty() ? fs::path("out") / "compare" : fs::path(args.out);
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw io::IoError(out.string() + ": cannot create the output directory: " + ec.message());

  const bool progress = show_progress(args.quiet);
  std::vector<core::RunResult> results;
  results.reserve(scenes.size());
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    scene::Scene& s = scenes[i];
    s.run.stop = &sys::interrupt_flag();
    results.push_back(simulate_scene(s, progress));
    const core::RunResult& r = results.back();
    if (r.interrupted) throw sys::Interrupted{};  // a comparison of partial runs would mislead
    if (r.instability) {
      print_instability(s.name, s.run, *r.instability, suggested_dt(s, checks[i]));
      return kExitUnstable;
    }
    if (!args.quiet) {
      std::printf("%s: %s, dt = %g s, %g s simulated in %.3f s", labels[i].c_str(),
                  s.run.integrator.c_str(), s.run.dt, s.run.duration, r.wall_seconds);
      for (const auto& [event, time] : event_times(r))
        std::printf("; %s %.4g s", event.c_str(), time);
      std::printf("\n");
      std::fflush(stdout);
    }
  }

  std::vector<plot::Run> runs;
  for (std::size_t i = 0; i < scenes.size(); ++i)
    runs.push_back({labels[i], &results[i].trajectory});
  std::vector<core::ColumnInfo> columns;
  for (const scene::Scene& s : scenes) {
    for (const core::ColumnInfo& c : core::column_infos(*s.network)) {
      if (std::none_of(columns.begin(), columns.end(),
                       [&](const core::ColumnInfo& k) { return k.name == c.name; })) {
        columns.push_back(c);
      }
    }
  }
  plot::PlotSpec spec = args.signals.empty() ? plot::default_comparison_spec(runs)
                                             : plot::comparison_spec(runs, args.signals, columns);
  if (args.signals.empty()) {
    // Units for the default panels, from the components.
    for (plot::PanelSpec& panel : spec.panels) {
      if (!panel.unit.empty() || panel.signals.empty()) continue;
      const auto info =
          std::find_if(columns.begin(), columns.end(),
                       [&](const core::ColumnInfo& c) { return c.name == panel.signals.front(); });
      if (info != columns.end()) panel.unit = info->unit;
    }
  }
  const plot::Format format = args.plot_format.value_or(plot::Format::png);
  const fs::path path = out / (std::string("compare") + plot::extension(format));
  plot::write_comparison_plot(spec, runs, path, format);
  if (!args.quiet) std::printf("  wrote %s\n", path.c_str());
  return kExitOk;
}

}  // namespace stiction::app
