// libstiction_render_plugin.so: render::render_outputs behind a C entry point (see
// render_plugin_api.hpp).
#include <exception>

#include "image/image.hpp"
#include "render/gl.hpp"
#include "render/render_plugin_api.hpp"
#include "render/video_encoder.hpp"
#include "text/font.hpp"

extern "C" __attribute__((visibility("default"))) void stiction_render_outputs_v1(
    stiction::render::PluginCall* call) {
  using stiction::render::PluginError;
  try {
    *call->result = stiction::render::render_outputs(*call->scene, *call->trajectory, *call->settings,
                                                     *call->request);
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
