// The pictures of a run, as `stiction run` writes them and the Python module draws them: the
// video (and --frames) through the render plugin, the rows the figures and the video are
// drawn from, and the times of the video's frames. A streaming run thins its rows as they
// come (StreamedRows); a run that kept every row (the Python module's) thins them here in the
// same way, so that its figures and frames are the command line's to the byte.
#pragma once

#include <atomic>
#include <filesystem>
#include <string>
#include <vector>

#include "core/simulation.hpp"
#include "core/trajectory.hpp"
#include "render/render_outputs.hpp"
#include "render/render_settings.hpp"
#include "render/time_warp.hpp"
#include "scene/scene.hpp"

namespace stiction::services {

// Every stick and slip event time of the run, element after element: the video slows down
// around them when [render] slow_motion_around_events is set.
std::vector<double> slip_event_times(const core::RunResult& result);
// Their kinds ("stick", "slip", "open"), in the same order: the video's inset marks them.
std::vector<std::string> slip_event_kinds(const core::RunResult& result);

// From every row of a run, the rows `stiction run` keeps for its plots
// (StreamedRows::for_plots) and for its video and frames (StreamedRows::for_video).
core::Trajectory plot_rows(const core::Trajectory& all);
core::Trajectory video_rows(const core::Trajectory& all, const core::RunOptions& run,
                            const render::RenderSettings& settings);

// The simulated time and playback speed of every frame of the video (frame i of video.mp4
// is frames/NNNNNN.png with NNNNNN = i), for `rows` as video_rows gives them; `events` and
// `kinds` as slip_event_times and slip_event_kinds give them.
std::vector<render::FrameTime> video_frame_times(const core::Trajectory& rows,
                                                 const render::RenderSettings& settings,
                                                 const std::vector<double>& events,
                                                 const std::vector<std::string>& kinds);

struct VideoRequest {
  std::filesystem::path out_dir;  // OUT/video.mp4, OUT/frames/
  bool video = true;
  bool frames = false;
  bool progress = false;                      // a progress bar on stderr
  const std::atomic<bool>* cancel = nullptr;  // set: stop, keep OUT/video.partial.mp4
};

// OUT/video.mp4 and with `frames` OUT/frames/NNNNNN.png of a run, drawn from `rows` (as
// video_rows gives them). Throws what render::render_outputs throws.
render::RenderResult write_run_video(const scene::Scene& scene, const core::RunResult& result,
                                     const core::Trajectory& rows,
                                     const render::RenderSettings& settings,
                                     const VideoRequest& request);

}  // namespace stiction::services
