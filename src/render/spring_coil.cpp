#include "render/spring_coil.hpp"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <numbers>

#include "render/arrow.hpp"

namespace stiction::render {

std::vector<glm::vec3> coil_path(const glm::vec3& from, const glm::vec3& to,
                                 const CoilShape& shape) {
  const glm::vec3 d = to - from;
  const float length = glm::length(d);
  if (!(length > 1e-6f * shape.coil_radius)) return {from, to};
  const glm::vec3 axis = d / length;
  const glm::mat4 basis = rotation_to(axis);
  const glm::vec3 e1(basis[0]), e2(basis[1]);
  const glm::vec3 start = from + shape.lead_fraction * d;
  const glm::vec3 end = to - shape.lead_fraction * d;
  const int n = std::max(1, shape.turns * shape.segments_per_turn);
  std::vector<glm::vec3> path{from, start};
  // The helix leaves the axis and comes back to it over its first and last half turn, so the
  // leads join the coil without a kink across the whole radius.
  for (int i = 1; i < n; ++i) {  // 0 and n are `start` and `end`
    const float s = static_cast<float>(i) / static_cast<float>(n);
    const float phase = 2.0f * std::numbers::pi_v<float> * static_cast<float>(shape.turns) * s;
    const float ramp = std::min({1.0f, s * 2.0f * static_cast<float>(shape.turns),
                                 (1.0f - s) * 2.0f * static_cast<float>(shape.turns)});
    const glm::vec3 centre = start + s * (end - start);
    path.push_back(centre +
                   ramp * shape.coil_radius * (std::cos(phase) * e1 + std::sin(phase) * e2));
  }
  path.push_back(end);
  path.push_back(to);
  return path;
}

void add_tube(std::vector<DrawItem>& items, const std::vector<glm::vec3>& path, float radius,
              const Material& material, bool casts_shadow) {
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    const glm::vec3 d = path[i + 1] - path[i];
    const float length = glm::length(d);
    if (!(length > 1e-7f)) continue;
    DrawItem item;
    item.shape = Shape::cylinder;  // radius 1 along z from -1 to 1
    // Each piece a little longer than its segment, so the corners of the tube close.
    item.model =
        glm::translate(glm::mat4(1.0f), 0.5f * (path[i] + path[i + 1])) * rotation_to(d / length) *
        glm::scale(glm::mat4(1.0f), glm::vec3(radius, radius, 0.5f * length + 0.5f * radius));
    item.material = material;
    item.casts_shadow = casts_shadow;
    items.push_back(item);
  }
}

}  // namespace stiction::render
