// The directional light's shadow map fitted, every frame, to what can show a shadow: the
// light-space footprint of the shadow casters, cut down to the part of the ground the camera
// can see. The map's texels then stay small whatever the length of the run (no stair-stepped
// shadow edges on a 13 m roll), and the soft edge is set in world units (a fixed fraction of
// the viewing distance) rather than in texels, so a smaller map gives the same picture as
// long as its texels stay well below that edge.
#pragma once

#include <array>
#include <glm/glm.hpp>
#include <vector>

#include "render/camera.hpp"
#include "render/scene_view.hpp"

namespace stiction::render {

struct ShadowFit {
  bool empty = true;                // no caster can shadow anything visible
  // World -> light clip space: x and y of the fitted region map to [-1, 1], a map of
  // `size` x `size` texels.
  glm::mat4 light_view_proj{1.0f};
  int size = 0;                     // texels per side of the map (<= map_size)
  float texel = 0.0f;               // world size of one texel
  float depth_range = 1.0f;         // metres spanned by depth 0..1
  float softness = 0.0f;            // world width of the filtered edge (tap offset)
  // Where the casters are, in the light's view (a rigid world -> light transform; x, y
  // across the light, z along it, larger z nearer the light): their footprint and the
  // largest z of any caster. Only points behind that depth and over that footprint (widened
  // by the filter's reach) can read a shadow (render/shadow_region.hpp).
  glm::mat4 light_view{1.0f};
  glm::vec2 casters_min{0.0f}, casters_max{0.0f};
  float casters_near = 0.0f;
};

// `aspect`: the frame's width / height; `map_size`: the most texels per side of a map: the
// fit uses the power of two (>= 256) that makes a texel at most a quarter
// of the soft edge, so the cost follows what the picture needs.
// The corners of an item's unit shape ([-1, 1]^3; a plane's is flat, z = 0) in world
// coordinates: a box around it that turns with it.
std::array<glm::vec3, 8> shape_corners(const DrawItem& item);

ShadowFit fit_shadow(const std::vector<DrawItem>& items, const Camera& camera, float aspect,
                     glm::vec3 light_direction, int map_size);

}  // namespace stiction::render
