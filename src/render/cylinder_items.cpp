#include "render/cylinder_items.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include "render/scene_geometry.hpp"

namespace stiction::render {
namespace {

const glm::vec3 kCylinderColour{0.80f, 0.62f, 0.18f};  // brass
const glm::vec3 kCylinderColour2{0.92f, 0.90f, 0.84f};
const glm::vec3 kBoreColour{0.08f, 0.08f, 0.09f};

}  // namespace

void add_cylinder(std::vector<DrawItem>& items, const BodyVisual& b, int index,
                  const core::Vec3& position, const core::Quat& orientation) {
  // The unit cylinder mesh: radius 1, z in [-1, 1]; its z onto the body-frame axis.
  core::Vec3 t1, t2;
  tangents(b.axis, t1, t2);
  const glm::mat4 frame = glm::translate(glm::mat4(1.0f), to_glm(position)) *
                          to_glm(orientation) * rotation_from_basis(t1, t2, b.axis);
  const float r = static_cast<float>(b.radius), h = 0.5f * static_cast<float>(b.length);
  DrawItem body;
  body.shape = Shape::cylinder;
  body.model = frame * glm::scale(glm::mat4(1.0f), glm::vec3(r, r, h));
  body.material.kind = MaterialKind::sphere_pattern;
  body.material.colour = kCylinderColour;
  body.material.colour2 = kCylinderColour2;
  body.material.shininess = 48.0f;
  body.material.specular = 0.4f;
  body.body = index;
  items.push_back(body);
  if (!b.hollow) return;
  // A ring: a dark disc just proud of each cap, 80% of the radius, reads as its bore.
  DrawItem bore;
  bore.shape = Shape::cylinder;
  bore.model = frame * glm::scale(glm::mat4(1.0f), glm::vec3(0.8f * r, 0.8f * r, 1.01f * h));
  bore.material.colour = kBoreColour;
  bore.casts_shadow = false;
  items.push_back(bore);
}

}  // namespace stiction::render
