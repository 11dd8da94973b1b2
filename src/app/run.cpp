// `stiction run`: simulate, write trajectory.csv and summary.json, then the plots and the
// video (DESIGN sections 3 and 4). Render and plot settings are read before the simulation
// so that a bad [render] table or a plot naming an unknown signal fails at once (exit 2).
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "app/event_lines.hpp"
#include "core/column_info.hpp"
#include "core/simulation.hpp"
#include "image/image.hpp"
#include "io/atomic_file.hpp"
#include "io/csv_writer.hpp"
#include "io/summary.hpp"
#include "plot/plot_spec.hpp"
#include "render/gl.hpp"
#include "render/render_outputs.hpp"
#include "render/render_settings.hpp"
#include "render/video_encoder.hpp"
#include "scene/scene.hpp"
#include "services/interrupted_run.hpp"
#include "services/output_dir.hpp"
#include "services/plot_outputs.hpp"
#include "services/run_outputs.hpp"
#include "services/run_service.hpp"
#include "services/run_support.hpp"
#include "services/step_guard.hpp"
#include "services/streamed_rows.hpp"
#include "services/verify_settings.hpp"
#include "sys/interrupt.hpp"
#include "text/font.hpp"

namespace stiction::app {
using namespace services;
namespace fs = std::filesystem;

namespace {

// The signal groups the default figures leave out beyond their cap, named (a few, then the
// count) with how to draw them.
void print_not_drawn(const std::vector<std::string>& groups) {
  if (groups.empty()) return;
  std::string names;
  for (std::size_t i = 0; i < groups.size() && i < 8; ++i) names.append(i ? ", " : "").append(groups[i]);
  if (groups.size() > 8) names.append(" and ").append(std::to_string(groups.size() - 8)).append(" more");
  std::printf("  not drawn (the default figures stop at %d): %zu signal groups: %s; draw them with "
              "[[plots]] in the scene or `stiction compare --signals`\n",
              plot::kMaxDefaultFigures, groups.size(), names.c_str());
}

}  // namespace

int run_command(const RunArguments& args) {
  RunRequest request;
  request.overrides = {args.integrator, args.dt, args.duration, args.tolerance};
  request.force_step = args.force_step;
  request.accuracy = args.accuracy;
  request.check_frames = !args.no_video || args.frames;
  request.progress = show_progress(args.quiet);
  request.stop = &sys::interrupt_flag();
  // Interrupted while loading: nothing was written, nothing to keep.
  const auto interrupted_in_load = [&] { return interrupted_exit(args.quiet, "load", {}); };
  PreparedRun prepared = prepare_run(scene::load_scene(args.scene, args.overrides), request);
  if (sys::interrupted()) return interrupted_in_load();
  if (!args.quiet) {
    for (const scene::Warning& w : prepared.warnings)
      std::fprintf(stderr, "%s\n", scene::format_warning(w).c_str());
  }
  guard_run(prepared, request);
  const scene::Scene& scene = prepared.scene;
  const core::RunOptions& run = scene.run;
  const StepGuard& guard = prepared.guard;
  if (guard.refusal) {
    print_refusal(scene.name, guard);
    return kExitUnstable;
  }
  if (guard.warning && !args.quiet)
    std::fprintf(stderr, "%s\n", scene::format_warning(prepared.warnings.back()).c_str());
  // Staged (services/output_dir.hpp): the files land in the directory only at out.commit(),
  // also for an interrupted or unstable run; an error leaves the earlier run's files as they were.
  OutputDirectory out(args.out.empty() ? fs::path("out") / scene.name : fs::path(args.out),
                      OutputOptions{args.overwrite});

  // Streaming: rows go to trajectory.csv as they are produced; plots and the video get
  // thinned copies (StreamedRows), so memory does not grow with the run's length.
  const bool video_or_frames = !args.no_video || args.frames;
  StreamedRows rows(out / "trajectory.csv", prepared.columns, run, prepared.render_settings,
                    !args.no_plots, video_or_frames);
  RunOutcome outcome = simulate_run(prepared, request, &rows.sink());
  const core::RunResult& result = outcome.result;
  nlohmann::ordered_json& summary = outcome.summary;
  const AccuracyEstimate& accuracy = outcome.accuracy;
  const double time_reached = outcome.time_reached;
  const render::RenderSettings& render_settings = prepared.render_settings;
  const bool progress = request.progress;

  rows.commit_csv();  // the rows up to the last complete one, also when interrupted
  out.wrote(out / "trajectory.csv");
  // summary.json lists the files written so far, itself included; it is written again
  // after the plots and the video with the complete list.
  const auto write_summary = [&](const char* interrupted_in) {
    if (interrupted_in != nullptr) mark_interrupted(summary, interrupted_in, time_reached);
    out.wrote(out / "summary.json");
    summary["files"] = out.files();
    io::write_summary(summary, out / "summary.json");
  };
  // The run's error estimate (docs/accuracy.md): a companion run, for finished runs only,
  // after the rows are safe on disk.
  estimate_run_accuracy(prepared, request, outcome);
  if (outcome.accuracy_interrupted) {
    write_summary("accuracy");
    out.commit();
    return interrupted_exit(args.quiet, "accuracy", out.files(), time_reached);
  }
  write_summary(result.interrupted ? "simulate" : nullptr);
  if (result.interrupted) {
    out.commit();
    return interrupted_exit(args.quiet, "simulate", out.files(), time_reached);
  }

  if (result.instability) {
    // The rows up to the instability are in the CSV; pictures of a diverging run are not
    // worth the time, so the plots and the video are skipped.
    print_instability(scene.name, run, *result.instability, *outcome.suggestion);
    out.commit();
    if (!args.quiet) {
      std::fprintf(stderr, "  wrote %s and %s (rows up to the instability); no plots or video\n",
                   out.final_path("trajectory.csv").c_str(), out.final_path("summary.json").c_str());
    }
    return kExitUnstable;
  }
  if (!args.quiet) {
    std::printf("%s: %s, dt = %g s, %ld steps, %d rows in %.3f s\n", scene.name.c_str(),
                run.integrator.c_str(), run.dt, result.steps, static_cast<int>(result.rows),
                result.wall_seconds);
    for (const std::string& line : event_lines(summary["events"], summary["accuracy"]))
      std::printf("  %s\n", line.c_str());
    for (const std::string& line : body_event_lines(summary["bodies"]))
      std::printf("  %s\n", line.c_str());
    std::printf("  wrote %s and %s\n", out.final_path("trajectory.csv").c_str(),
                out.final_path("summary.json").c_str());
    std::fflush(stdout);
  }
  if (!args.quiet && accuracy.verdict == "inaccurate") print_inaccurate(scene.name, run, accuracy);

  if (!args.no_plots) {
    try {
      const std::vector<fs::path> plots = write_run_plots(
          prepared.plot_specs, result, rows.for_plots(), out / "plots", args.plot_format);
      for (const fs::path& p : plots) out.wrote(p);
      if (sys::interrupted()) {
        write_summary("plots");
        out.commit();
        return interrupted_exit(args.quiet, "plots", out.files(), time_reached);
      }
      if (!args.quiet) {
        for (const fs::path& p : plots) std::printf("  wrote %s\n", out.final_path(p).c_str());
        print_not_drawn(prepared.plots_not_drawn);
        std::fflush(stdout);
      }
    } catch (const text::FontError& e) {
      std::fprintf(stderr, "error: plots: %s\n", e.what());
      return kExitFailure;
    } catch (const image::ImageError& e) {
      std::fprintf(stderr, "error: plots: %s\n", e.what());
      return kExitFailure;
    } catch (const io::IoError& e) {
      std::fprintf(stderr, "error: plots: %s\n", e.what());
      return kExitFailure;
    }
  }

  if (!args.no_video || args.frames) {
    render::RenderResult rendered;
    try {
      VideoRequest video;
      video.out_dir = out.path();
      video.video = !args.no_video;
      video.frames = args.frames;
      video.progress = progress;
      video.cancel = &sys::interrupt_flag();
      rendered = write_run_video(scene, result, rows.for_video(), render_settings, video);
    } catch (const scene::InputError&) {
      throw;  // exit 2, message already located
    } catch (const render::GlError& e) {
      std::fprintf(stderr, "error: OpenGL (OSMesa): %s\n  (--no-video skips rendering)\n",
                   e.what());
      return kExitFailure;
    } catch (const render::VideoError& e) {
      std::fprintf(stderr, "error: video: %s\n", e.what());
      return kExitFailure;
    } catch (const render::RenderError& e) {
      std::fprintf(stderr, "error: render: %s\n", e.what());
      return kExitFailure;
    } catch (const image::ImageError& e) {
      std::fprintf(stderr, "error: frames: %s\n", e.what());
      return kExitFailure;
    } catch (const text::FontError& e) {
      std::fprintf(stderr, "error: overlay font: %s\n", e.what());
      return kExitFailure;
    }
    const double fps = rendered.wall_seconds > 0.0 ? rendered.frames / rendered.wall_seconds : 0.0;
    if (args.frames) {
      for (int i = 0; i < rendered.frames; ++i) out.wrote(out / "frames" / frame_name(i));
    }
    if (!rendered.video.empty()) out.wrote(rendered.video);
    if (rendered.interrupted) {
      std::fprintf(stderr, "interrupted: rendered %d frames", rendered.frames);
      if (!rendered.video.empty())
        std::fprintf(stderr, "; the partial video is %s", out.final_path(rendered.video).c_str());
      std::fprintf(stderr, "\n");
      write_summary("render");
      out.commit();
      return interrupted_exit(args.quiet, "render", out.files(), time_reached);
    }
    if (!args.quiet) {
      if (!rendered.video.empty()) {
        std::printf("  wrote %s (%d frames, %dx%d at %g fps, rendered in %.1f s: %.1f frames/s)\n",
                    out.final_path(rendered.video).c_str(), rendered.frames, render_settings.width,
                    render_settings.height, render_settings.fps, rendered.wall_seconds, fps);
      }
      if (args.frames) {
        std::printf("  wrote %s/000000.png .. %06d.png\n", out.final_path("frames").c_str(),
                    rendered.frames - 1);
      }
    }
  }
  if (!args.no_plots || !args.no_video || args.frames) write_summary(nullptr);  // the full list
  out.commit();  // the new files replace the earlier run's only now
  return kExitOk;
}

}  // namespace stiction::app
