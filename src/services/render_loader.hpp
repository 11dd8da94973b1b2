// Loads the renderer on demand (fast start): `run --no-video`, `check`, `scenes` and the
// other commands never map OSMesa, LLVM or libav, which cost about 0.36 s and 70 MiB at
// start-up when linked. The plugin is $STICTION_RENDER_PLUGIN when that is set; otherwise it
// is looked for in <directory of the executable>/../<libdir>/stiction/ (an installed,
// possibly moved, prefix), then in the build tree.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "image/image.hpp"
#include "render/compare_video.hpp"
#include "render/render_outputs.hpp"
#include "render/render_settings.hpp"
#include "render/time_warp.hpp"
#include "scene/scene.hpp"

namespace stiction::services {

// render::render_outputs through the plugin. Throws what render_outputs throws
// (render::GlError, VideoError, RenderError, image::ImageError, text::FontError,
// scene::InputError); render::RenderError when the plugin cannot be loaded.
render::RenderResult render_outputs_on_demand(const scene::Scene& scene,
                                              const core::Trajectory& trajectory,
                                              const render::RenderSettings& settings,
                                              const render::RenderRequest& request);

// Single frames of one run through the plugin (`stiction verify`): `choose_times` gets the
// run's frame clock and returns the times to render.
struct RenderedFrames {
  std::vector<double> times;
  std::vector<image::Image> images;
};
// `event_times` / `event_kinds`: the run's events (slip_event_times / slip_event_kinds), which
// an [inset] plot marks as the video does.
RenderedFrames render_frames_on_demand(
    const scene::Scene& scene, const core::Trajectory& trajectory,
    const render::RenderSettings& settings,
    const std::function<std::vector<double>(const render::FrameClock&)>& choose_times,
    const std::vector<double>& event_times = {}, const std::vector<std::string>& event_kinds = {});

// The frames of one run at the given times, each drawn at its playback speed as the video
// draws it (the Python module's stiction.frame; services/run_outputs.hpp gives the video's
// frame times). One GL context for all of them.
std::vector<image::Image> render_frames_at(const scene::Scene& scene,
                                           const core::Trajectory& trajectory,
                                           const render::RenderSettings& settings,
                                           const std::vector<render::FrameTime>& times,
                                           const std::vector<double>& event_times = {},
                                           const std::vector<std::string>& event_kinds = {});

// `stiction compare ... --video` through the plugin: the runs side by side in
// OUT/compare.mp4 (render/compare_video.hpp). Throws as render_outputs_on_demand.
render::RenderResult render_compare_video_on_demand(const std::vector<render::CompareRun>& runs,
                                                    const render::CompareVideoRequest& request);

}  // namespace stiction::services
