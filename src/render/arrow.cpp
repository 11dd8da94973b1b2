#include "render/arrow.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace stiction::render {

glm::mat4 rotation_to(const glm::vec3& axis) {
  // A helper axis far from `axis`, so the cross products stay well conditioned.
  const glm::vec3 helper =
      std::abs(axis.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  const glm::vec3 x = glm::normalize(glm::cross(helper, axis));
  const glm::vec3 y = glm::cross(axis, x);
  glm::mat4 r(1.0f);
  r[0] = glm::vec4(x, 0.0f);
  r[1] = glm::vec4(y, 0.0f);
  r[2] = glm::vec4(axis, 0.0f);
  return r;
}

void add_arrow(std::vector<DrawItem>& items, const glm::vec3& tail, const glm::vec3& vector,
               const Material& material, const ArrowStyle& style) {
  const float length = glm::length(vector);
  if (!(length > 1e-3f * style.shaft_radius) || !std::isfinite(length)) return;
  const glm::vec3 direction = vector / length;
  const float head_radius = 2.2f * style.shaft_radius;
  const float head = std::min(
      style.head_length > 0.0f ? style.head_length : 5.0f * style.shaft_radius, 0.5f * length);
  const float shaft = length - head;
  const glm::mat4 rotation = rotation_to(direction);

  DrawItem shaft_item;
  shaft_item.shape = Shape::cylinder;  // radius 1 along z from -1 to 1
  shaft_item.model =
      glm::translate(glm::mat4(1.0f), tail + 0.5f * shaft * direction) * rotation *
      glm::scale(glm::mat4(1.0f), glm::vec3(style.shaft_radius, style.shaft_radius, 0.5f * shaft));
  shaft_item.material = material;
  shaft_item.casts_shadow = style.casts_shadow;
  items.push_back(shaft_item);

  DrawItem head_item;
  head_item.shape = Shape::cone;  // base radius 1 at z = 0, apex at z = 1
  head_item.model = glm::translate(glm::mat4(1.0f), tail + shaft * direction) * rotation *
                    glm::scale(glm::mat4(1.0f), glm::vec3(head_radius, head_radius, head));
  head_item.material = material;
  head_item.casts_shadow = style.casts_shadow;
  items.push_back(head_item);
}

}  // namespace stiction::render
