// An off-screen OpenGL 3.3 core context. This interface is the only thing the renderer knows
// of the backend: OSMesa today (Mesa <= 25.0); an EGL surfaceless backend can be added as
// another implementation of GlContext without touching the renderer.
#pragma once

#include <memory>
#include <string>

#include "render/gl.hpp"

namespace stiction::render {

class GlContext {
 public:
  virtual ~GlContext() = default;
  GlContext() = default;
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  // Makes the context current on the calling thread (it is current after creation).
  virtual void make_current() = 0;
  // "OSMesa", "EGL", ...
  virtual std::string backend() const = 0;
  // GL_RENDERER and GL_VERSION strings, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  std::string renderer() const;
  std::string version() const;
  int max_samples() const;
};

// Creates an off-screen OpenGL >= 3.3 core-profile context and makes it current.
// Throws GlError with a clear message if the backend is missing or gives less than 3.3.
std::unique_ptr<GlContext> create_offscreen_context();

}  // namespace stiction::render
