// libstiction_render_plugin.so: render::render_outputs behind a C entry point (see
// render_plugin_api.hpp).
#include <exception>

#include "image/image.hpp"
#include "render/gl.hpp"
#include "render/render_outputs.hpp"
#include "render/render_plugin_api.hpp"
#include "render/scene_view.hpp"
#include "render/video_encoder.hpp"
#include "text/font.hpp"

namespace {

using stiction::render::PluginError;

// Runs `work`, turning the exceptions the renderer throws into an error kind and a message
// (exceptions do not cross the plugin boundary).
template <typename Call, typename Work>
void guarded(Call* call, Work&& work) {
  try {
    work();
    call->error = PluginError::none;
  } catch (const stiction::scene::InputError& e) {
    call->error = PluginError::input;
    call->message = e.what();
  } catch (const stiction::render::GlError& e) {
    call->error = PluginError::gl;
    call->message = e.what();
  } catch (const stiction::render::VideoError& e) {
    call->error = PluginError::video;
    call->message = e.what();
  } catch (const stiction::render::RenderError& e) {
    call->error = PluginError::render;
    call->message = e.what();
  } catch (const stiction::image::ImageError& e) {
    call->error = PluginError::image;
    call->message = e.what();
  } catch (const stiction::text::FontError& e) {
    call->error = PluginError::font;
    call->message = e.what();
  } catch (const std::exception& e) {
    call->error = PluginError::other;
    call->message = e.what();
  }
}

}  // namespace

extern "C" __attribute__((visibility("default"))) void stiction_render_outputs_v4(
    stiction::render::PluginCall* call) {
  guarded(call, [call] {
    *call->result = stiction::render::render_outputs(*call->scene, *call->trajectory,
                                                     *call->settings, *call->request);
  });
}

extern "C" __attribute__((visibility("default"))) void stiction_render_frames_v5(
    stiction::render::FramesCall* call) {
  namespace render = stiction::render;
  guarded(call, [call] {
    const std::unique_ptr<render::FrameRenderer> made = render::frame_renderer_for(
        *call->scene, *call->trajectory, *call->settings, call->event_times, call->event_kinds);
    render::FrameRenderer& renderer = *made;
    const render::FrameClock clock =
        render::frame_clock(renderer.poses().start_time(), renderer.poses().end_time(),
                            call->settings->fps, call->settings->slow_motion);
    call->times = call->choose(clock);
    call->images.clear();
    for (std::size_t i = 0; i < call->times.size(); ++i) {
      const double speed = i < call->speeds.size() ? call->speeds[i] : 1.0;
      call->images.push_back(renderer.render(call->times[i], speed));
    }
  });
}

extern "C" __attribute__((visibility("default"))) void stiction_render_compare_v3(
    stiction::render::CompareVideoCall* call) {
  guarded(call, [call] {
    *call->result = stiction::render::render_compare_video(*call->runs, *call->request);
  });
}
