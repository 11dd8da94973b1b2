// `stiction compare SCENE SCENE...`: runs each scene as `run --no-video --no-plots` would
// and overlays them in one figure, OUT/compare.png (default out/compare/), drawn by
// services/comparison.hpp; this file parses the scene arguments, guards and simulates the
// runs and prints. With --video it also writes OUT/compare.mp4, the runs side by side
// (render/compare_video.hpp, through the renderer plugin).
// A scene argument may carry overrides of its own after '@' ("sphere_roll@ground.mu=0.3");
// each run is labelled by its scene name plus the overrides that tell it from the others.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "core/column_info.hpp"
#include "render/compare_video.hpp"
#include "render/render_settings.hpp"
#include "scene/scene.hpp"
#include "services/comparison.hpp"
#include "services/progress.hpp"
#include "services/render_loader.hpp"
#include "services/run_outputs.hpp"
#include "services/run_support.hpp"
#include "services/step_guard.hpp"
#include "sys/interrupt.hpp"
#include "text/number_text.hpp"

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
  std::vector<std::vector<std::string>> own_overrides, signal_columns;
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    names.push_back(scenes[i].name);
    own_overrides.push_back(requests[i].overrides);
    signal_columns.push_back(scenes[i].network->signal_columns());
  }
  const std::vector<std::string> labels = comparison_labels(names, own_overrides);

  // --signals is checked against the scenes' columns before anything runs (exit 2 at once).
  check_comparison_signals(labels, signal_columns, args.signals);

  // With --video, every scene's [render]/[camera]/[overlay]/[inset] is checked before the
  // first simulation too (exit 2 at once).
  std::vector<render::RenderSettings> render_settings;
  if (args.video) {
    for (const scene::Scene& s : scenes) {
      render_settings.push_back(render::read_render_settings(s));
      render::check_frame_count(s, render_settings.back());
    }
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
  make_comparison_directory(out);

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
      // The user's values shortest round-trip, measured ones with stated digits (every event
      // time, stick or slip, with the same count).
      std::printf("%s: %s, dt = %s s, %s s simulated in %s s", labels[i].c_str(),
                  s.run.integrator.c_str(), text::shortest(s.run.dt).c_str(),
                  text::shortest(s.run.duration).c_str(),
                  text::significant(r.wall_seconds, 3).c_str());
      for (const auto& [event, time] : event_times(r))
        std::printf("; %s %s s", event.c_str(),
                    text::significant(time, text::kEventTimeDigits).c_str());
      std::printf("\n");
      std::fflush(stdout);
    }
  }

  std::vector<ComparedRun> runs;
  for (std::size_t i = 0; i < scenes.size(); ++i)
    runs.push_back({labels[i], &results[i].trajectory, core::column_infos(*scenes[i].network)});
  const fs::path path =
      write_comparison(runs, args.signals, out, args.plot_format.value_or(plot::Format::png));
  if (!args.quiet) std::printf("  wrote %s\n", path.c_str());
  std::fflush(stdout);  // before the video's progress lines on stderr
  if (args.video) {
    std::vector<render::CompareRun> video_runs;
    for (std::size_t i = 0; i < scenes.size(); ++i) {
      render::CompareRun run;
      run.label = labels[i];
      run.scene = &scenes[i];
      run.trajectory = &results[i].trajectory;
      run.settings = render_settings[i];
      run.event_times = slip_event_times(results[i]);
      run.event_kinds = slip_event_kinds(results[i]);
      video_runs.push_back(std::move(run));
    }
    render::CompareVideoRequest request;
    request.out_dir = out;
    request.cancel = &sys::interrupt_flag();
    std::unique_ptr<ProgressBar> bar;
    if (progress) {
      bar = std::make_unique<ProgressBar>("render compare video");
      request.progress = [&bar](const render::RenderProgress& p) {
        bar->frames(p.frames_done, p.frame_count, p.frames_per_second, p.eta_seconds);
      };
    }
    const render::RenderResult video = render_compare_video_on_demand(video_runs, request);
    if (video.interrupted) {
      // The figure and the frames so far are kept; main() turns this into exit 130 / 143.
      std::fprintf(stderr, "interrupted: %s holds the %d frames rendered\n", video.video.c_str(),
                   video.frames);
      return kExitOk;
    }
    if (bar) bar->finish(std::to_string(video.frames) + " frames");
    if (!args.quiet) std::printf("  wrote %s\n", video.video.c_str());
  }
  return kExitOk;
}

}  // namespace stiction::app
