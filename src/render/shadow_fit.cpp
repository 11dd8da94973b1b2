#include "render/shadow_fit.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace stiction::render {
namespace {

// Light-space boxes: x, y across the light, z along it (towards the light is +z in view).
struct Box2 {
  glm::vec2 min{1e30f}, max{-1e30f};
  void add(glm::vec2 p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  bool empty() const { return min.x > max.x || min.y > max.y; }
};

// Rounds `v` up to the next of 2^(k/4): the footprint's size changes in steps of ~19%, so
// it (and with it the texel grid) stays the same over many frames instead of every frame.
float quantize_up(float v) {
  const float k = std::ceil(4.0f * std::log2(std::max(v, 1e-6f)));
  return std::exp2(k / 4.0f);
}

}  // namespace

std::array<glm::vec3, 8> shape_corners(const DrawItem& item) {
  const float z = item.shape == Shape::plane ? 0.0f : 1.0f;
  std::array<glm::vec3, 8> corners;
  for (int i = 0; i < 8; ++i) {
    const glm::vec4 local((i & 1) ? 1.0f : -1.0f, (i & 2) ? 1.0f : -1.0f, (i & 4) ? z : -z, 1.0f);
    corners[static_cast<std::size_t>(i)] = glm::vec3(item.model * local);
  }
  return corners;
}

ShadowFit fit_shadow(const std::vector<DrawItem>& items, const Camera& camera, float aspect,
                     glm::vec3 light_direction, int map_size) {
  ShadowFit fit;
  const glm::vec3 l = glm::normalize(light_direction);
  const glm::vec3 up = std::abs(l.z) > 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1);
  // A light view through the origin; the fitted box is positioned in its coordinates.
  const glm::mat4 light_view = glm::lookAt(glm::vec3(0.0f), -l, up);
  const float distance = glm::length(camera.eye - camera.target);
  fit.softness = 0.002f * distance;

  // Casters.
  Box2 casters;
  float z_near = -1e30f, z_far = 1e30f;  // view-space z: larger is nearer the light
  for (const DrawItem& item : items) {
    if (!item.casts_shadow) continue;
    if (item.shape == Shape::sphere) {
      // Its own footprint, a disc: the box of a turned sphere is up to sqrt(3) too wide.
      const glm::vec3 c = glm::vec3(light_view * item.model[3]);
      const float r = std::max({glm::length(glm::vec3(item.model[0])),
                                glm::length(glm::vec3(item.model[1])),
                                glm::length(glm::vec3(item.model[2]))});
      casters.add(glm::vec2(c) - r);
      casters.add(glm::vec2(c) + r);
      z_near = std::max(z_near, c.z + r);
      z_far = std::min(z_far, c.z - r);
      continue;
    }
    for (const glm::vec3& corner : shape_corners(item)) {
      const glm::vec3 p = glm::vec3(light_view * glm::vec4(corner, 1.0f));
      casters.add(glm::vec2(p));
      z_near = std::max(z_near, p.z);
      z_far = std::min(z_far, p.z);
    }
  }
  if (casters.empty()) return fit;
  fit.light_view = light_view;
  fit.casters_min = casters.min;
  fit.casters_max = casters.max;
  fit.casters_near = z_near;

  // Visible receivers: the camera's frustum out to where the fog has hidden the ground.
  Box2 visible;
  const glm::mat4 inverse = glm::inverse(camera.projection(aspect) * camera.view());
  const float fog_end = 6.0f * distance;
  for (int i = 0; i < 8; ++i) {
    const glm::vec4 ndc((i & 1) ? 1.0f : -1.0f, (i & 2) ? 1.0f : -1.0f, -1.0f, 1.0f);
    glm::vec4 w = inverse * ndc;
    glm::vec3 near_point = glm::vec3(w) / w.w;
    glm::vec3 ray = glm::normalize(near_point - camera.eye);
    // Far corners at the fog's end (the far plane is much farther away).
    const glm::vec3 p = (i & 4) ? camera.eye + ray * fog_end : near_point;
    visible.add(glm::vec2(light_view * glm::vec4(p, 1.0f)));
  }

  // Where a visible shadow can be: the casters' footprint, widened by the soft edge and by
  // a caster's reach along the light to the ground, cut to the visible region.
  const float margin = 4.0f * fit.softness + 1e-4f;
  Box2 region;
  region.min = glm::max(casters.min - margin, visible.min);
  region.max = glm::min(casters.max + margin, visible.max);
  if (region.empty()) return fit;
  fit.empty = false;

  // A square map: the larger side, quantized, centred on the region and snapped to texels
  // so the texel grid does not crawl as the region moves.
  const float side =
      quantize_up(std::max(region.max.x - region.min.x, region.max.y - region.min.y));
  fit.size = 256;
  while (fit.size < map_size && side / static_cast<float>(fit.size) > 0.25f * fit.softness)
    fit.size *= 2;
  fit.size = std::min(fit.size, std::max(map_size, 1));
  fit.texel = side / static_cast<float>(fit.size);
  glm::vec2 centre = 0.5f * (region.min + region.max);
  centre = glm::floor(centre / fit.texel + 0.5f) * fit.texel;
  const float half = 0.5f * side;
  // Depth: from just in front of the nearest caster to just behind the farthest; receivers
  // farther from the light read the far value (the shader clamps), which is right for a
  // directional light (anything behind a caster's depth is in its shadow).
  const float pad = 0.05f * (z_near - z_far) + 4.0f * fit.texel + 1e-4f;
  const float n = -(z_near + pad), f = -(z_far - pad);
  fit.depth_range = f - n;
  fit.light_view_proj =
      glm::ortho(centre.x - half, centre.x + half, centre.y - half, centre.y + half, n, f) *
      light_view;
  return fit;
}

}  // namespace stiction::render
