// The renderer as a plugin (fast start, issue 14): `stiction` does not link OSMesa, LLVM
// and libav; it loads libstiction_render_plugin.so with dlopen only when a run renders a
// video or frames (app/render_loader.hpp). This is the one entry point, with the same
// arguments as render::render_outputs. Both sides are built from this source tree by the
// same compiler, so C++ types cross the boundary; exceptions do not (they are turned into
// an error kind and a message, and thrown again on the application's side).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/trajectory.hpp"
#include "image/image.hpp"
#include "render/compare_video.hpp"
#include "render/render_outputs.hpp"
#include "render/render_settings.hpp"
#include "scene/scene.hpp"

namespace stiction::render {

enum class PluginError { none = 0, gl, video, render, image, font, input, other };

struct PluginCall {
  const scene::Scene* scene = nullptr;
  const core::Trajectory* trajectory = nullptr;
  const RenderSettings* settings = nullptr;
  const RenderRequest* request = nullptr;
  RenderResult* result = nullptr;
  PluginError error = PluginError::none;
  std::string message;
};

// Single frames of one run (`stiction verify`): `choose` gets the run's frame clock and
// returns the times to render; the plugin fills `times` and `images` (one per time).
struct FramesCall {
  const scene::Scene* scene = nullptr;
  const core::Trajectory* trajectory = nullptr;
  const RenderSettings* settings = nullptr;
  std::function<std::vector<double>(const FrameClock&)> choose;
  // The playback speed of each chosen time (FrameTime::speed; the overlay and the motion blur
  // show it as the video does); empty: 1.
  std::vector<double> speeds;
  // The run's events (the inset marks them), as RenderRequest's.
  std::vector<double> event_times;
  std::vector<std::string> event_kinds;
  std::vector<double> times;
  std::vector<image::Image> images;
  PluginError error = PluginError::none;
  std::string message;
};

// `stiction compare ... --video`: the runs side by side in OUT/compare.mp4
// (render/compare_video.hpp).
struct CompareVideoCall {
  const std::vector<CompareRun>* runs = nullptr;
  const CompareVideoRequest* request = nullptr;
  RenderResult* result = nullptr;
  PluginError error = PluginError::none;
  std::string message;
};

// Bumped whenever PluginCall, FramesCall, CompareVideoCall or the types they point to change.
inline constexpr const char* kRenderPluginSymbol = "stiction_render_outputs_v4";
using RenderPluginEntry = void (*)(PluginCall*);
inline constexpr const char* kRenderFramesSymbol = "stiction_render_frames_v5";
using RenderFramesEntry = void (*)(FramesCall*);
inline constexpr const char* kRenderCompareSymbol = "stiction_render_compare_v3";
using RenderCompareEntry = void (*)(CompareVideoCall*);

}  // namespace stiction::render
