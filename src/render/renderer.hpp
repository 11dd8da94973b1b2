// Draws a list of items into a multisampled framebuffer object with a directional light's
// shadow map, resolves it and reads it back as an image::Image (top row first).
// Needs a current GlContext (>= 3.3 core) for its whole life.
#pragma once

#include <array>
#include <map>
#include <memory>
#include <vector>

#include "image/image.hpp"
#include "render/camera.hpp"
#include "render/gl.hpp"
#include "render/mesh.hpp"
#include "render/scene_view.hpp"
#include "render/shader.hpp"

namespace stiction::render {

struct RendererOptions {
  int width = 1280;
  int height = 720;
  int msaa = 4;                // 1: no multisampling
  int shadow_map_size = 2048;  // 0: no shadows; else the most texels per side used
  int shadow_taps = 4;         // 1 or 4
  // Sample the shadow map over the whole frame instead of only where a shadow can fall: the
  // reference that render/shadow_region.hpp is tested against (same picture, slower).
  bool shadows_everywhere = false;
  image::Rgba background{236, 239, 243, 255};
};

// Towards the light: from the upper left and a little from the front, so shadows fall to the
// right of the bodies where the default camera (from -y) sees them.
inline glm::vec3 light_direction() { return glm::normalize(glm::vec3(-0.6f, -0.25f, 1.0f)); }

class Renderer {
 public:
  explicit Renderer(const RendererOptions& options);

  // The shadow map is fitted to the casters and the visible ground each frame
  // (render/shadow_fit.hpp) and sampled only where a shadow can fall
  // (render/shadow_region.hpp). `trail`: a triangle strip drawn unlit over the ground (may be
  // empty).
  void draw(const std::vector<DrawItem>& items, const Camera& camera,
            const std::vector<TrailVertex>& trail = {});
  // Resolves the multisampled image and reads it into `out` (resized as needed).
  void read_back(image::Image& out);
  image::Image read_back();

  const RendererOptions& options() const { return options_; }

 private:
  const Mesh& mesh(const DrawItem& item);
  // Draws the item's mesh; a mirroring model matrix (a URDF mesh's negative scale) turns
  // its triangles' winding, so the front faces are then the clockwise ones.
  void draw_mesh(const DrawItem& item);

  RendererOptions options_;
  // The lit program of a material, with or without shadow sampling (both compiled in:
  // shaders/scene.frag.glsl), built the first time it is asked for.
  ShaderProgram& scene_program(MaterialKind kind, bool shadowed);
  static std::size_t program_slot(MaterialKind kind, bool shadowed) {
    return 2 * static_cast<std::size_t>(kind) + (shadowed ? 1 : 0);
  }
  std::array<std::unique_ptr<ShaderProgram>, 6> scene_programs_;
  ShaderProgram depth_program_;
  ShaderProgram trail_program_;
  Mesh sphere_, box_, cylinder_, cone_, plane_;
  // The URDF mesh parts drawn so far, uploaded on first use. Each entry holds its mesh, so
  // that a part's address is never reused by another while it is a key here.
  struct UploadedPart {
    std::shared_ptr<const scene::TriangleMesh> owner;
    std::unique_ptr<Mesh> mesh;
  };
  std::map<const scene::TriangleMesh::Part*, UploadedPart> mesh_parts_;
  GlVertexArray trail_vao_;
  GlBuffer trail_buffer_;
  // Multisampled colour + depth and the single-sampled resolve target.
  GlFramebuffer msaa_fbo_, resolve_fbo_;
  GlRenderbuffer msaa_colour_, msaa_depth_, resolve_colour_;
  // A shadow map per size the fit asks for (powers of two up to shadow_map_size), made on
  // first use: the map is cleared whole, which llvmpipe does fast, where a scissored clear
  // of a corner of one large map took it a full-screen draw (5 ms a frame at 1024^2).
  struct ShadowTarget {
    GlFramebuffer fbo;
    GlTexture map;
  };
  ShadowTarget& shadow_target(int size);
  std::map<int, ShadowTarget> shadow_targets_;
  std::vector<std::uint8_t> rows_;  // read-back scratch (bottom row first)
};

}  // namespace stiction::render
