#include "services/render_loader.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "image/image.hpp"
#include "render/gl.hpp"
#include "render/render_plugin_api.hpp"
#include "render/video_encoder.hpp"
#include "sys/data_dirs.hpp"
#include "text/font.hpp"

namespace stiction::services {
namespace fs = std::filesystem;
namespace {

std::vector<fs::path> plugin_candidates() {
  std::vector<fs::path> paths;
  if (const char* env = std::getenv("STICTION_RENDER_PLUGIN"); env != nullptr && *env != '\0') {
    return {fs::path(env)};  // an explicit choice: nothing else
  }
  if (!sys::install_root().empty()) {
    paths.push_back(sys::install_root() / STICTION_PLUGIN_RELATIVE_DIR /
                    "libstiction_render_plugin.so");
  }
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec)
    paths.push_back(exe.parent_path() / ".." / STICTION_PLUGIN_RELATIVE_DIR /
                    "libstiction_render_plugin.so");
  paths.emplace_back(STICTION_RENDER_PLUGIN_BUILD_PATH);
  return paths;
}

// Loaded once, kept for the process's lifetime (the renderer's threads and libav's state
// must not outlive an unloaded library).
void* open_plugin() {
  std::string tried;
  for (const fs::path& path : plugin_candidates()) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) {
      tried += "\n  " + path.string() + ": not found";
      continue;
    }
    void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
      tried += "\n  " + path.string() + ": " + ::dlerror();
      continue;
    }
    if (::dlsym(handle, render::kRenderPluginSymbol) != nullptr &&
        ::dlsym(handle, render::kRenderFramesSymbol) != nullptr &&
        ::dlsym(handle, render::kRenderCompareSymbol) != nullptr) {
      return handle;
    }
    tried += "\n  " + path.string() + ": no " + render::kRenderPluginSymbol + " (another version?)";
  }
  throw render::RenderError("cannot load the renderer (libstiction_render_plugin.so):" + tried);
}

// A function-local static: thread-safe on first use (verify renders scenes in parallel); a
// failed load throws and is tried again on the next call.
void* load_plugin() {
  static void* const plugin = open_plugin();
  return plugin;
}

template <typename Entry>
Entry entry_point(const char* symbol) {
  return reinterpret_cast<Entry>(::dlsym(load_plugin(), symbol));
}

// Throws on the application's side what the plugin caught on its side.
void rethrow(render::PluginError error, const std::string& message) {
  switch (error) {
    case render::PluginError::none:
      return;
    case render::PluginError::gl:
      throw render::GlError(message);
    case render::PluginError::video:
      throw render::VideoError(message);
    case render::PluginError::render:
      throw render::RenderError(message);
    case render::PluginError::image:
      throw image::ImageError(message);
    case render::PluginError::font:
      throw text::FontError(message);
    case render::PluginError::input:
      throw scene::InputError(message);
    case render::PluginError::other:
      break;
  }
  throw render::RenderError(message);
}

}  // namespace

render::RenderResult render_outputs_on_demand(const scene::Scene& scene,
                                              const core::Trajectory& trajectory,
                                              const render::RenderSettings& settings,
                                              const render::RenderRequest& request) {
  const auto entry = entry_point<render::RenderPluginEntry>(render::kRenderPluginSymbol);
  render::RenderResult result;
  render::PluginCall call;
  call.scene = &scene;
  call.trajectory = &trajectory;
  call.settings = &settings;
  call.request = &request;
  call.result = &result;
  entry(&call);
  rethrow(call.error, call.message);
  return result;
}

RenderedFrames render_frames_on_demand(
    const scene::Scene& scene, const core::Trajectory& trajectory,
    const render::RenderSettings& settings,
    const std::function<std::vector<double>(const render::FrameClock&)>& choose_times,
    const std::vector<double>& event_times, const std::vector<std::string>& event_kinds) {
  const auto entry = entry_point<render::RenderFramesEntry>(render::kRenderFramesSymbol);
  render::FramesCall call;
  call.scene = &scene;
  call.trajectory = &trajectory;
  call.settings = &settings;
  call.choose = choose_times;
  call.event_times = event_times;
  call.event_kinds = event_kinds;
  entry(&call);
  rethrow(call.error, call.message);
  return {std::move(call.times), std::move(call.images)};
}

std::vector<image::Image> render_frames_at(const scene::Scene& scene,
                                           const core::Trajectory& trajectory,
                                           const render::RenderSettings& settings,
                                           const std::vector<render::FrameTime>& times,
                                           const std::vector<double>& event_times,
                                           const std::vector<std::string>& event_kinds) {
  const auto entry = entry_point<render::RenderFramesEntry>(render::kRenderFramesSymbol);
  render::FramesCall call;
  call.scene = &scene;
  call.trajectory = &trajectory;
  call.settings = &settings;
  call.event_times = event_times;
  call.event_kinds = event_kinds;
  std::vector<double> chosen;
  for (const render::FrameTime& f : times) {
    chosen.push_back(f.t);
    call.speeds.push_back(f.speed);
  }
  call.choose = [&chosen](const render::FrameClock&) { return chosen; };
  entry(&call);
  rethrow(call.error, call.message);
  return std::move(call.images);
}

render::RenderResult render_compare_video_on_demand(const std::vector<render::CompareRun>& runs,
                                                    const render::CompareVideoRequest& request) {
  const auto entry = entry_point<render::RenderCompareEntry>(render::kRenderCompareSymbol);
  render::RenderResult result;
  render::CompareVideoCall call;
  call.runs = &runs;
  call.request = &request;
  call.result = &result;
  entry(&call);
  rethrow(call.error, call.message);
  return result;
}

}  // namespace stiction::services
