// Arrows as draw items (force sources, contact forces, velocities): a cylinder shaft and a
// cone head, lit and shaded like the bodies so that their direction in depth reads.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "render/scene_view.hpp"

namespace stiction::render {

struct ArrowStyle {
  float shaft_radius = 0.005f;  // metres; the head is 2.2x as wide
  float head_length = 0.0f;     // metres; 0: 5 shaft radii (at most half the arrow)
  bool casts_shadow = false;    // overlays do not shadow the scene
};

// Adds the arrow from `tail` along `vector` (world metres) to `items`. An arrow shorter than
// a thousandth of its shaft radius adds nothing (a zero force has no direction to show).
void add_arrow(std::vector<DrawItem>& items, const glm::vec3& tail, const glm::vec3& vector,
               const Material& material, const ArrowStyle& style = {});

// Rotation taking the unit shapes' z axis to the unit vector `axis` (any completion of the
// basis; the shapes it is used for are round about z).
glm::mat4 rotation_to(const glm::vec3& axis);

}  // namespace stiction::render
