// `stiction compare SCENE SCENE...`: runs each scene as `run --no-video --no-plots` would
// and overlays them in one figure, OUT/compare.png (default out/compare/). The arm scenes
// get the drift comparison (joint angles and their change after the arm stopped); other
// runs a figure of the signals they have in common.
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "app/run_support.hpp"
#include "io/atomic_file.hpp"
#include "plot/plot_spec.hpp"
#include "scene/scene.hpp"
#include "sys/interrupt.hpp"

namespace stiction::app {
namespace fs = std::filesystem;

int compare_command(const CompareArguments& args) {
  if (args.scenes.size() < 2) {
    throw scene::InputError("error: compare needs at least two scenes (got " +
                            std::to_string(args.scenes.size()) + ")");
  }
  // Every scene is loaded (and checked) before the first simulation starts.
  std::vector<scene::Scene> scenes;
  for (const std::string& name : args.scenes) {
    scenes.push_back(scene::load_scene(name, args.overrides));
    apply_overrides(scenes.back(), {});
  }
  const fs::path out = args.out.empty() ? fs::path("out") / "compare" : fs::path(args.out);
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw io::IoError(out.string() + ": cannot create the output directory: " + ec.message());

  const bool progress = show_progress(args.quiet);
  std::vector<core::RunResult> results;
  results.reserve(scenes.size());
  for (scene::Scene& s : scenes) {
    s.run.stop = &sys::interrupt_flag();
    results.push_back(simulate_scene(s, progress));
    const core::RunResult& r = results.back();
    if (r.interrupted) throw sys::Interrupted{};  // a comparison of partial runs would mislead
    if (r.instability) {
      print_instability(s.name, s.run, *r.instability, suggested_dt(s));
      return kExitUnstable;
    }
    if (!args.quiet) {
      std::printf("%s: %s, dt = %g s, %g s simulated in %.3f s", s.name.c_str(),
                  s.run.integrator.c_str(), s.run.dt, s.run.duration, r.wall_seconds);
      for (const auto& [event, time] : event_times(r)) std::printf("; %s %.4g s", event.c_str(), time);
      std::printf("\n");
      std::fflush(stdout);
    }
  }

  // Runs are labelled by scene name; the same name twice (one scene file under two paths)
  // gets its position appended so the legend stays unambiguous.
  std::map<std::string, int> uses;
  for (const scene::Scene& s : scenes) ++uses[s.name];
  std::vector<plot::Run> runs;
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    std::string label = scenes[i].name;
    if (uses[label] > 1) label += " (" + std::to_string(i + 1) + ")";
    runs.push_back({label, &results[i].trajectory});
  }
  const plot::PlotSpec spec = plot::default_comparison_spec(runs);
  const fs::path png = out / "compare.png";
  plot::write_comparison_plot(spec, runs, png);
  if (!args.quiet) std::printf("  wrote %s\n", png.c_str());
  return kExitOk;
}

}  // namespace stiction::app
