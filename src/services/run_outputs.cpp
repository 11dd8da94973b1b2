#include "services/run_outputs.hpp"

#include <limits>
#include <memory>
#include <string>

#include "core/row_sink.hpp"
#include "services/progress.hpp"
#include "services/render_loader.hpp"
#include "services/streamed_rows.hpp"

namespace stiction::services {
namespace {

// Replays every row into a thinned copy, as the streaming run does block by block (the
// thinning depends on the row index only, not on the blocks).
core::Trajectory replay(const core::Trajectory& all, core::DecimatedTrajectory&& thinned) {
  if (all.row_count() > 0) {
    thinned.write(all.row(0), static_cast<std::size_t>(all.row_count()),
                  static_cast<std::size_t>(all.column_count()));
  }
  thinned.finish();
  return thinned.trajectory();
}

}  // namespace

std::vector<double> slip_event_times(const core::RunResult& result) {
  std::vector<double> times;
  for (const core::SlipHistory& h : result.slip_events) {
    for (const core::SlipEvent& e : h.monitor.events()) times.push_back(e.time);
  }
  return times;
}

std::vector<std::string> slip_event_kinds(const core::RunResult& result) {
  std::vector<std::string> kinds;
  for (const core::SlipHistory& h : result.slip_events) {
    for (const core::SlipEvent& e : h.monitor.events()) kinds.push_back(e.kind);
  }
  return kinds;
}

core::Trajectory plot_rows(const core::Trajectory& all) {
  return replay(all, core::DecimatedTrajectory(all.columns(), StreamedRows::kPlotRows));
}

core::Trajectory video_rows(const core::Trajectory& all, const core::RunOptions& run,
                            const render::RenderSettings& settings) {
  // Never thinned beyond the stride, as StreamedRows keeps them.
  return replay(
      all, core::DecimatedTrajectory(all.columns(), std::numeric_limits<std::size_t>::max() / 2,
                                     StreamedRows::video_stride(run, settings)));
}

std::vector<render::FrameTime> video_frame_times(const core::Trajectory& rows,
                                                 const render::RenderSettings& settings,
                                                 const std::vector<double>& events,
                                                 const std::vector<std::string>& kinds) {
  if (rows.row_count() == 0) return {};
  // As render::render_outputs: the frame clock from the first to the last row
  // (render::frame_clock's step), warped around the events.
  const double start = rows.at(0, 0);
  const double end = rows.at(rows.row_count() - 1, 0);
  const double step = 1.0 / (settings.fps * settings.slow_motion);
  return render::warped_frame_times(
      start, end, step,
      render::slowed_events(events, kinds, settings.slow_motion_around_events,
                            settings.slowed_events),
      settings.slow_motion_around_events, settings.event_slow_motion);
}

render::RenderResult write_run_video(const scene::Scene& scene, const core::RunResult& result,
                                     const core::Trajectory& rows,
                                     const render::RenderSettings& settings,
                                     const VideoRequest& video) {
  std::unique_ptr<ProgressBar> bar;
  render::RenderRequest request;
  request.out_dir = video.out_dir;
  request.video = video.video;
  request.frames = video.frames;
  request.cancel = video.cancel;
  request.event_times = slip_event_times(result);  // time-warp around events
  request.event_kinds = slip_event_kinds(result);
  if (video.progress) {
    bar = std::make_unique<ProgressBar>(video.video ? "render video" : "render frames");
    request.progress = [&bar](const render::RenderProgress& p) {
      bar->frames(p.frames_done, p.frame_count, p.frames_per_second, p.eta_seconds);
    };
  }
  render::RenderResult rendered = render_outputs_on_demand(scene, rows, settings, request);
  if (bar && !rendered.interrupted) bar->finish(std::to_string(rendered.frames) + " frames");
  return rendered;
}

}  // namespace stiction::services
