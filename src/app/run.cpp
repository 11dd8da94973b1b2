// `stiction run`: simulate, write trajectory.csv and summary.json, then the plots and the
// video (DESIGN sections 3 and 4). Render and plot settings are read before the simulation
// so that a bad [render] table or a plot naming an unknown signal fails at once (exit 2).
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <regex>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "app/progress.hpp"
#include "app/run_support.hpp"
#include "app/streamed_rows.hpp"
#include "core/simulation.hpp"
#include "image/image.hpp"
#include "io/atomic_file.hpp"
#include "io/csv_writer.hpp"
#include "io/summary.hpp"
#include "plot/plot_spec.hpp"
#include "render/gl.hpp"
#include "render/render_outputs.hpp"
#include "render/render_settings.hpp"
#include "render/scene_view.hpp"
#include "render/video_encoder.hpp"
#include "scene/scene.hpp"
#include "text/font.hpp"

namespace stiction::app {
namespace fs = std::filesystem;
namespace {

// Frames of an earlier, longer run would sit beside the new ones and look like part of it.
void remove_old_frames(const fs::path& frames_dir) {
  std::error_code ec;
  if (!fs::is_directory(frames_dir, ec)) return;
  static const std::regex frame_name("[0-9]{6}\\.png");
  std::vector<fs::path> old;
  for (const auto& entry : fs::directory_iterator(frames_dir, ec)) {
    if (std::regex_match(entry.path().filename().string(), frame_name)) old.push_back(entry.path());
  }
  for (const fs::path& p : old) fs::remove(p, ec);
}

// Writes every plot; returns the files written.
std::vector<fs::path> write_plots(const std::vector<plot::PlotSpec>& specs,
                                  const core::RunResult& result, const core::Trajectory& rows,
                                  const fs::path& dir) {
  const std::map<std::string, double> events = event_times(result);
  std::vector<fs::path> written;
  for (const plot::PlotSpec& spec : specs) {
    const fs::path png = dir / (spec.name + ".png");
    plot::write_plot(spec, rows, events, png);
    written.push_back(png);
  }
  return written;
}

render::RenderResult write_video(const scene::Scene& scene, const core::Trajectory& rows,
                                 const render::RenderSettings& settings, const fs::path& out,
                                 bool video, bool frames, bool progress) {
  std::atomic<bool> interrupted{false};
  InterruptFlag on_ctrl_c(interrupted);
  std::unique_ptr<ProgressBar> bar;
  render::RenderRequest request;
  request.out_dir = out;
  request.video = video;
  request.frames = frames;
  request.cancel = &interrupted;
  if (progress) {
    bar = std::make_unique<ProgressBar>(video ? "render video" : "render frames");
    request.progress = [&bar](const render::RenderProgress& p) {
      bar->frames(p.frames_done, p.frame_count, p.frames_per_second, p.eta_seconds);
    };
  }
  if (frames) remove_old_frames(out / "frames");
  return render::render_outputs(scene, rows, settings, request);
}

}  // namespace

int run_command(const RunArguments& args) {
  scene::Scene scene = scene::load_scene(args.scene, args.overrides);
  apply_overrides(scene, {args.integrator, args.dt, args.duration, args.tolerance});
  const core::RunOptions& run = scene.run;

  // Checked before the simulation: both fail with file:line:col on a bad table or signal.
  const render::RenderSettings render_settings = render::read_render_settings(scene);
  std::vector<std::string> columns = scene.network->signal_columns();
  columns.insert(columns.begin(), "t");
  std::vector<plot::PlotSpec> plot_specs =
      plot::read_plot_specs(scene.document, scene.path.string(), columns);
  if (plot_specs.empty()) plot_specs = plot::default_plot_specs(columns);

  const fs::path out = args.out.empty() ? fs::path("out") / scene.name : fs::path(args.out);
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw io::IoError(out.string() + ": cannot create the output directory: " + ec.message());

  // Streaming: rows go to trajectory.csv as they are produced; plots and the video get
  // thinned copies (StreamedRows), so memory does not grow with the run's length.
  const bool video_or_frames = !args.no_video || args.frames;
  StreamedRows rows(out / "trajectory.csv", columns, run, render_settings, !args.no_plots,
                    video_or_frames);
  const bool progress = show_progress(args.quiet);
  const core::RunResult result = simulate_scene(scene, progress, &rows.sink());

  io::RunDescription description;
  description.scene = scene.name;
  description.integrator = run.integrator;
  description.dt = run.dt;
  description.duration = run.duration;
  description.output_rate = run.output_rate;
  description.state_dim = scene.network->state_dim();
  if (run.tolerance > 0.0) description.tolerance = run.tolerance;
  if (result.instability) description.suggested_dt = suggested_dt(scene);

  const auto summary = io::make_summary(description, result);
  rows.commit_csv();
  io::write_summary(summary, out / "summary.json");

  if (result.instability) {
    // The rows up to the instability are in the CSV; pictures of a diverging run are not
    // worth the time, so the plots and the video are skipped.
    print_instability(scene.name, run, *result.instability, *description.suggested_dt);
    if (!args.quiet) {
      std::fprintf(stderr, "  wrote %s and %s (rows up to the instability); no plots or video\n",
                   (out / "trajectory.csv").c_str(), (out / "summary.json").c_str());
    }
    return kExitUnstable;
  }
  if (!args.quiet) {
    std::printf("%s: %s, dt = %g s, %ld steps, %d rows in %.3f s\n", scene.name.c_str(),
                run.integrator.c_str(), run.dt, result.steps, static_cast<int>(result.rows),
                result.wall_seconds);
    for (const auto& [contact, entry] : summary["events"].items()) {
      if (entry["stick_time"].is_null()) {
        std::printf("  %s: no stick\n", contact.c_str());
      } else {
        std::printf("  %s: stick at t = %.6g s\n", contact.c_str(), entry["stick_time"].get<double>());
      }
    }
    std::printf("  wrote %s and %s\n", (out / "trajectory.csv").c_str(), (out / "summary.json").c_str());
    std::fflush(stdout);
  }

  if (!args.no_plots) {
    try {
      const std::vector<fs::path> plots =
          write_plots(plot_specs, result, rows.for_plots(), out / "plots");
      if (!args.quiet) {
        for (const fs::path& p : plots) std::printf("  wrote %s\n", p.c_str());
        std::fflush(stdout);
      }
    } catch (const text::FontError& e) {
      std::fprintf(stderr, "error: plots: %s\n", e.what());
      return kExitFailure;
    } catch (const image::ImageError& e) {
      std::fprintf(stderr, "error: plots: %s\n", e.what());
      return kExitFailure;
    }
  }

  if (!args.no_video || args.frames) {
    render::RenderResult rendered;
    try {
      rendered = write_video(scene, rows.for_video(), render_settings, out, !args.no_video, args.frames,
                             progress);
    } catch (const scene::InputError&) {
      throw;  // exit 2, message already located
    } catch (const render::GlError& e) {
      std::fprintf(stderr, "error: OpenGL (OSMesa): %s\n  (--no-video skips rendering)\n", e.what());
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
    if (rendered.interrupted) {
      std::fprintf(stderr, "interrupted: rendered %d frames", rendered.frames);
      if (!rendered.video.empty()) std::fprintf(stderr, "; the partial video is %s", rendered.video.c_str());
      std::fprintf(stderr, "\n");
      return kExitInterrupted;
    }
    if (!rendered.video.empty()) {
      fs::remove(out / "video.partial.mp4", ec);  // left by an earlier, interrupted run
    }
    if (!args.quiet) {
      if (!rendered.video.empty()) {
        std::printf("  wrote %s (%d frames, %dx%d at %g fps, rendered in %.1f s: %.1f frames/s)\n",
                    rendered.video.c_str(), rendered.frames, render_settings.width,
                    render_settings.height, render_settings.fps, rendered.wall_seconds, fps);
      }
      if (args.frames) {
        std::printf("  wrote %s/000000.png .. %06d.png\n", (out / "frames").c_str(),
                    rendered.frames - 1);
      }
    }
  }
  return kExitOk;
}

}  // namespace stiction::app
