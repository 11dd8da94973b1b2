// The renderer as a plugin (fast start, issue 14): `stiction` does not link OSMesa, LLVM
// and libav; it loads libstiction_render_plugin.so with dlopen only when a run renders a
// video or frames (app/render_loader.hpp). This is the one entry point, with the same
// arguments as render::render_outputs. Both sides are built from this source tree by the
// same compiler, so C++ types cross the boundary; exceptions do not (they are turned into
// an error kind and a message, and thrown again on the application's side).
#pragma once

#include <string>

#include "core/trajectory.hpp"
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

// Bumped whenever PluginCall or the types it points to change.
inline constexpr const char* kRenderPluginSymbol = "stiction_render_outputs_v1";
using RenderPluginEntry = void (*)(PluginCall*);

}  // namespace stiction::render
