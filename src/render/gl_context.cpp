#include "render/gl_context.hpp"

#include <GL/osmesa.h>

#include <vector>

namespace stiction::render {

std::string GlContext::renderer() const {
  const auto* s = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return s ? s : "";
}

std::string GlContext::version() const {
  const auto* s = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  return s ? s : "";
}

int GlContext::max_samples() const {
  GLint samples = 0;
  glGetIntegerv(GL_MAX_SAMPLES, &samples);
  return samples;
}

namespace {

// OSMesa renders into a client buffer; the renderer draws into its own framebuffer objects,
// so this buffer only has to exist for OSMesaMakeCurrent.
class OsMesaContext final : public GlContext {
 public:
  OsMesaContext() : buffer_(kSize * kSize * 4) {
    const int attributes[] = {OSMESA_FORMAT,
                              OSMESA_RGBA,
                              OSMESA_DEPTH_BITS,
                              0,
                              OSMESA_STENCIL_BITS,
                              0,
                              OSMESA_PROFILE,
                              OSMESA_CORE_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION,
                              3,
                              OSMESA_CONTEXT_MINOR_VERSION,
                              3,
                              0};
    context_ = OSMesaCreateContextAttribs(attributes, nullptr);
    if (!context_) {
      throw GlError(
          "OSMesa could not create an OpenGL 3.3 core-profile context (is Mesa's libOSMesa "
          "with llvmpipe installed? Debian: libosmesa6)");
    }
    make_current();
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < 33) {
      OSMesaDestroyContext(context_);
      throw GlError("OSMesa gave OpenGL " + std::to_string(major) + "." + std::to_string(minor) +
                    "; the renderer needs 3.3 core");
    }
  }
  ~OsMesaContext() override {
    OSMesaMakeCurrent(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0);
    OSMesaDestroyContext(context_);
  }

  void make_current() override {
    if (!OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, kSize, kSize)) {
      throw GlError("OSMesaMakeCurrent failed");
    }
  }
  std::string backend() const override { return "OSMesa"; }

 private:
  static constexpr int kSize = 16;
  std::vector<unsigned char> buffer_;
  OSMesaContext context_ = nullptr;
};

}  // namespace

std::unique_ptr<GlContext> create_offscreen_context() {
  return std::make_unique<OsMesaContext>();
}

}  // namespace stiction::render
