#include "render/renderer.hpp"

#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "render/shadow_fit.hpp"
#include "render/shadow_region.hpp"

namespace stiction::render {
namespace {

const glm::vec3 kLightDirection = light_direction();

glm::vec3 linear(const image::Rgba& c) {
  auto f = [](std::uint8_t v) { return std::pow(v / 255.0f, 2.2f); };
  return {f(c.r), f(c.g), f(c.b)};
}

void check_framebuffer(const char* what) {
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    char code[16];
    std::snprintf(code, sizeof code, "0x%04x", status);
    throw GlError(std::string("incomplete framebuffer (") + what + "): status " + code);
  }
}

}  // namespace

Renderer::Renderer(const RendererOptions& options)
    : options_(options),
      depth_program_("depth.vert.glsl", "depth.frag.glsl"),
      trail_program_("trail.vert.glsl", "trail.frag.glsl"),
      sphere_(make_sphere(48, 24)),
      box_(make_box()),
      cylinder_(make_cylinder(32)),
      cone_(make_cone(24)),
      plane_(make_plane(16)),
      trail_vao_(make_vertex_array()),
      trail_buffer_(make_buffer()),
      msaa_fbo_(make_framebuffer()),
      resolve_fbo_(make_framebuffer()),
      msaa_colour_(make_renderbuffer()),
      msaa_depth_(make_renderbuffer()),
      resolve_colour_(make_renderbuffer()) {
  if (options.width <= 0 || options.height <= 0) throw GlError("frame size must be positive");
  GLint max_samples = 0;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  if (options.msaa > max_samples) {
    throw GlError("the GL driver allows at most " + std::to_string(max_samples) + "x MSAA, " +
                  std::to_string(options.msaa) + "x was asked for");
  }
  const int samples = options.msaa > 1 ? options.msaa : 0;
  glBindRenderbuffer(GL_RENDERBUFFER, msaa_colour_.get());
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, options.width,
                                   options.height);
  glBindRenderbuffer(GL_RENDERBUFFER, msaa_depth_.get());
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, options.width,
                                   options.height);
  glBindFramebuffer(GL_FRAMEBUFFER, msaa_fbo_.get());
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                            msaa_colour_.get());
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                            msaa_depth_.get());
  check_framebuffer("colour");

  glBindRenderbuffer(GL_RENDERBUFFER, resolve_colour_.get());
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, options.width, options.height);
  glBindFramebuffer(GL_FRAMEBUFFER, resolve_fbo_.get());
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                            resolve_colour_.get());
  check_framebuffer("resolve");

  glBindVertexArray(trail_vao_.get());
  glBindBuffer(GL_ARRAY_BUFFER, trail_buffer_.get());
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(TrailVertex),
                        reinterpret_cast<const void*>(offsetof(TrailVertex, position)));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(TrailVertex),
                        reinterpret_cast<const void*>(offsetof(TrailVertex, colour)));
  glBindVertexArray(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  check_gl("renderer set-up");
}

ShaderProgram& Renderer::scene_program(MaterialKind kind, bool shadowed) {
  std::unique_ptr<ShaderProgram>& slot = scene_programs_[program_slot(kind, shadowed)];
  if (!slot) {
    const std::string defines = "#define MATERIAL " + std::to_string(static_cast<int>(kind)) +
                                "\n#define SHADOWS " + (shadowed ? "1" : "0") +
                                "\n#define SHADOW_TAPS " +
                                std::to_string(options_.shadow_taps <= 1 ? 1 : 4) + "\n";
    slot = std::make_unique<ShaderProgram>("scene.vert.glsl", "scene.frag.glsl", defines);
  }
  return *slot;
}

Renderer::ShadowTarget& Renderer::shadow_target(int size) {
  auto found = shadow_targets_.find(size);
  if (found != shadow_targets_.end()) return found->second;
  ShadowTarget target{make_framebuffer(), make_texture()};
  glBindTexture(GL_TEXTURE_2D, target.map.get());
  glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, size, size, 0, GL_DEPTH_COMPONENT, GL_FLOAT,
               nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  glBindFramebuffer(GL_FRAMEBUFFER, target.fbo.get());
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, target.map.get(), 0);
  glDrawBuffer(GL_NONE);
  glReadBuffer(GL_NONE);
  check_framebuffer("shadow map");
  return shadow_targets_.emplace(size, std::move(target)).first->second;
}

const Mesh& Renderer::mesh(const DrawItem& item) {
  if (item.shape == Shape::mesh && item.mesh && item.mesh_part < item.mesh->parts.size()) {
    const scene::TriangleMesh::Part* part = &item.mesh->parts[item.mesh_part];
    UploadedPart& slot = mesh_parts_[part];
    if (!slot.mesh) {
      slot.owner = item.mesh;
      slot.mesh = std::make_unique<Mesh>(unit_mesh(*part));
    }
    return *slot.mesh;
  }
  switch (item.shape) {
    case Shape::sphere:
      return sphere_;
    case Shape::box:
      return box_;
    case Shape::cylinder:
      return cylinder_;
    case Shape::cone:
      return cone_;
    default:
      return plane_;
  }
}

void Renderer::draw_mesh(const DrawItem& item) {
  const bool mirrored = glm::determinant(glm::mat3(item.model)) < 0.0f;
  if (mirrored) glFrontFace(GL_CW);
  mesh(item).draw();
  if (mirrored) glFrontFace(GL_CCW);
}

void Renderer::draw(const std::vector<DrawItem>& items, const Camera& camera,
                    const std::vector<TrailVertex>& trail) {
  const float aspect = float(options_.width) / float(options_.height);
  const bool shadows = options_.shadow_map_size > 0;
  const ShadowFit fit =
      shadows ? fit_shadow(items, camera, aspect, kLightDirection, options_.shadow_map_size)
              : ShadowFit{};
  const bool cast = shadows && !fit.empty;

  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);

  GLuint shadow_map = 0;
  if (cast) {
    ShadowTarget& target = shadow_target(fit.size);
    shadow_map = target.map.get();
    glBindFramebuffer(GL_FRAMEBUFFER, target.fbo.get());
    glViewport(0, 0, fit.size, fit.size);
    glClear(GL_DEPTH_BUFFER_BIT);
    // Casters poking out of the fitted depth range are clamped, not clipped.
    glEnable(GL_DEPTH_CLAMP);
    depth_program_.use();
    depth_program_.set("u_light_view_proj", fit.light_view_proj);
    for (const DrawItem& item : items) {
      if (!item.casts_shadow) continue;
      depth_program_.set("u_model", item.model);
      draw_mesh(item);
    }
    glDisable(GL_DEPTH_CLAMP);
    // The lit pass samples this map: finish it here. Left to llvmpipe, the first draw that
    // samples a texture still being rendered waits for it in a way that cost about 8 ms of
    // wall and of CPU per 720p frame more (bench_render: cpu_ms 92 -> 78).
    glFinish();
  }

  glBindFramebuffer(GL_FRAMEBUFFER, msaa_fbo_.get());
  glViewport(0, 0, options_.width, options_.height);
  const image::Rgba bg = options_.background;
  glClearColor(bg.r / 255.0f, bg.g / 255.0f, bg.b / 255.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  const glm::mat4 view_proj = camera.projection(aspect) * camera.view();

  // The frame's uniforms, set in each program the first time it draws this frame.
  const float side = cast ? fit.texel * float(fit.size) : 1.0f;  // the map's width
  const float distance = glm::length(camera.eye - camera.target);
  auto set_frame_uniforms = [&](ShaderProgram& program) {
    program.set("u_view_proj", view_proj);
    program.set("u_light_view_proj", fit.light_view_proj);
    program.set("u_light_dir", kLightDirection);
    program.set("u_eye", camera.eye);
    program.set("u_background", linear(bg));
    program.set("u_fog_start", distance * 1.5f);
    program.set("u_fog_end", distance * 6.0f);
    program.set("u_shadow_map", 0);
    // The soft edge and the depth bias in world units, converted to the map's coordinates.
    program.set("u_shadow_kernel", glm::vec2(cast ? fit.softness / side : 0.0f));
    program.set("u_shadow_bias",
                cast ? (2.0f * fit.texel + 0.5f * fit.softness) / fit.depth_range : 0.0f);
    program.set("u_shadow_slope_bias",
                cast ? 4.0f * (fit.texel + fit.softness) / fit.depth_range : 0.0f);
  };
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, shadow_map);

  // Shadow sampling inside the region where a shadow can fall, none elsewhere: the items are
  // drawn once per rectangle (the scissor keeps the rectangles' pixels apart), in their
  // order, so ties in depth resolve as in one pass.
  struct Pass {
    PixelRect rect;
    bool shadowed;
  };
  std::vector<Pass> passes;
  const PixelRect region =
      !cast ? PixelRect{}
      : options_.shadows_everywhere
          ? PixelRect{0, 0, options_.width, options_.height}
          : shadow_region(items, fit, camera, options_.width, options_.height);
  if (!region.empty()) passes.push_back({region, true});
  for (const PixelRect& r : complement(region, options_.width, options_.height)) {
    passes.push_back({r, false});
  }
  std::array<bool, std::tuple_size_v<decltype(scene_programs_)>> prepared{};
  glEnable(GL_SCISSOR_TEST);
  for (const Pass& pass : passes) {
    glScissor(pass.rect.x0, pass.rect.y0, pass.rect.x1 - pass.rect.x0,
              pass.rect.y1 - pass.rect.y0);
    for (const DrawItem& item : items) {
      const Material& m = item.material;
      ShaderProgram& program = scene_program(m.kind, pass.shadowed);
      program.use();
      bool& frame_uniforms_set = prepared[program_slot(m.kind, pass.shadowed)];
      if (!frame_uniforms_set) {
        set_frame_uniforms(program);
        frame_uniforms_set = true;
      }
      program.set("u_model", item.model);
      program.set("u_normal_matrix", glm::inverseTranspose(glm::mat3(item.model)));
      program.set("u_colour", m.colour);
      program.set("u_colour2", m.colour2);
      program.set("u_shininess", m.shininess);
      program.set("u_specular", m.specular);
      program.set("u_checker_size", m.checker_size);
      program.set("u_grid_spacing", m.grid_spacing);
      program.set("u_local_scale", m.local_scale);
      program.set("u_local_offset", m.local_offset);
      program.set("u_spin_axis", m.spin_axis);
      program.set("u_spin_blur", m.spin_blur);
      draw_mesh(item);
    }
  }
  glDisable(GL_SCISSOR_TEST);

  if (trail.size() >= 4) {
    glDisable(GL_CULL_FACE);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(-1.0f, -4.0f);
    trail_program_.use();
    trail_program_.set("u_view_proj", view_proj);
    glBindVertexArray(trail_vao_.get());
    glBindBuffer(GL_ARRAY_BUFFER, trail_buffer_.get());
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(trail.size() * sizeof(TrailVertex)),
                 trail.data(), GL_STREAM_DRAW);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, static_cast<GLsizei>(trail.size()));
    glDisable(GL_POLYGON_OFFSET_FILL);
  }
  glBindVertexArray(0);
  check_gl("draw");
}

void Renderer::read_back(image::Image& out) {
  const int w = options_.width, h = options_.height;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, msaa_fbo_.get());
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_fbo_.get());
  glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, resolve_fbo_.get());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  if (out.width != w || out.height != h) out = image::Image(w, h);
  rows_.resize(out.pixels.size());
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rows_.data());
  check_gl("read-back");
  // GL rows come bottom-up.
  const std::size_t stride = out.stride();
  for (int y = 0; y < h; ++y) {
    std::memcpy(out.pixels.data() + static_cast<std::size_t>(y) * stride,
                rows_.data() + static_cast<std::size_t>(h - 1 - y) * stride, stride);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

image::Image Renderer::read_back() {
  image::Image out;
  read_back(out);
  return out;
}

}  // namespace stiction::render
