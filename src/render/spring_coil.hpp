// A coil spring as a polyline: a straight lead at each end and a helix between them, so a
// spring reads as a spring from any side (a zigzag seen edge on is a line), and its turns
// crowd together as it is compressed.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "render/scene_view.hpp"

namespace stiction::render {

struct CoilShape {
  float coil_radius = 0.02f;  // metres, the helix's radius about the line between the ends
  int turns = 8;
  int segments_per_turn = 10;
  float lead_fraction = 0.12f;  // of the length, straight at each end
};

// The coil's centre line from `from` to `to`: `from`, the helix's start, the helix points,
// its end, `to`. Degenerate ends (closer than a millionth of the coil radius) give the two
// points only.
std::vector<glm::vec3> coil_path(const glm::vec3& from, const glm::vec3& to,
                                 const CoilShape& shape);

// A tube of cylinders of radius `radius` along `path` (one per segment).
void add_tube(std::vector<DrawItem>& items, const std::vector<glm::vec3>& path, float radius,
              const Material& material, bool casts_shadow = true);

}  // namespace stiction::render
