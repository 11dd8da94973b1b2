#include "app/render_loader.hpp"

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <dlfcn.h>

#include "image/image.hpp"
#include "render/gl.hpp"
#include "render/render_plugin_api.hpp"
#include "render/video_encoder.hpp"
#include "text/font.hpp"

namespace stiction::app {
namespace fs = std::filesystem;
namespace {

std::vector<fs::path> plugin_candidates() {
  std::vector<fs::path> paths;
  if (const char* env = std::getenv("STICTION_RENDER_PLUGIN"); env != nullptr && *env != '\0') {
    return {fs::path(env)};  // an explicit choice: nothing else
  }
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) paths.push_back(exe.parent_path() / ".." / STICTION_PLUGIN_RELATIVE_DIR / "libstiction_render_plugin.so");
  paths.emplace_back(STICTION_RENDER_PLUGIN_BUILD_PATH);
  return paths;
}

// Loaded once, kept for the process's lifetime (the renderer's threads and libav's state
// must not outlive an unloaded library).
render::RenderPluginEntry load_entry() {
  static render::RenderPluginEntry entry = nullptr;
  if (entry != nullptr) return entry;
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
    entry = reinterpret_cast<render::RenderPluginEntry>(::dlsym(handle, render::kRenderPluginSymbol));
    if (entry != nullptr) return entry;
    tried += "\n  " + path.string() + ": no " + render::kRenderPluginSymbol + " (another version?)";
  }
  throw render::RenderError("cannot load the renderer (libstiction_render_plugin.so):" + tried);
}

}  // namespace

render::RenderResult render_outputs_on_demand(const scene::Scene& scene, const core::Trajectory& trajectory,
                                              const render::RenderSettings& settings,
                                              const render::RenderRequest& request) {
  const render::RenderPluginEntry entry = load_entry();
  render::RenderResult result;
  render::PluginCall call;
  call.scene = &scene;
  call.trajectory = &trajectory;
  call.settings = &settings;
  call.request = &request;
  call.result = &result;
  entry(&call);
  switch (call.error) {
    case render::PluginError::none: return result;
    case render::PluginError::gl: throw render::GlError(call.message);
    case render::PluginError::video: throw render::VideoError(call.message);
    case render::PluginError::render: throw render::RenderError(call.message);
    case render::PluginError::image: throw image::ImageError(call.message);
    case render::PluginError::font: throw text::FontError(call.message);
    case render::PluginError::input: throw scene::InputError(call.message);
    case render::PluginError::other: break;
  }
  throw render::RenderError(call.message);
}

}  // namespace stiction::app
