#include "render/tree_items.hpp"

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>
#include <utility>

#include "render/scene_geometry.hpp"

namespace stiction::render {
namespace {

const glm::vec3 kRodColour{0.10f, 0.28f, 0.62f};
const glm::vec3 kRodColour2{0.15f, 0.50f, 0.75f};
const glm::vec3 kJointColour{0.06f, 0.06f, 0.07f};

// Frame of a visual (link -1: the base).
components::LinkPose visual_frame(const BodyVisual& b, const std::vector<components::LinkPose>& links,
                                  const scene::UrdfVisual& v) {
  components::LinkPose at;
  if (v.link < 0) {
    at.p = b.tree->params().base_position;
    at.q = b.tree->params().base_orientation;
  } else {
    at = links[static_cast<std::size_t>(v.link)];
  }
  return {at.p + at.q * v.origin, at.q * v.rotation};
}

// The end points of each link's rods: its children's joints, or for a leaf twice its
// centre of mass from its joint.
std::vector<std::pair<core::Vec3, core::Vec3>> rods(const BodyVisual& b,
                                                    const std::vector<components::LinkPose>& p) {
  const auto& links = b.tree->params().links;
  std::vector<std::pair<core::Vec3, core::Vec3>> out;
  std::vector<bool> has_child(links.size(), false);
  for (std::size_t i = 0; i < links.size(); ++i) {
    const int parent = links[i].parent;
    const core::Vec3 from = parent < 0 ? b.tree->params().base_position
                                       : p[static_cast<std::size_t>(parent)].p;
    if (parent >= 0) has_child[static_cast<std::size_t>(parent)] = true;
    out.emplace_back(from, p[i].p);
  }
  for (std::size_t i = 0; i < links.size(); ++i) {
    if (!has_child[i] && links[i].com.norm() > 1e-9) {
      out.emplace_back(p[i].p, p[i].p + p[i].q * (2.0 * links[i].com));
    }
  }
  return out;
}

void add_rod(std::vector<DrawItem>& items, const core::Vec3& a, const core::Vec3& b, float radius,
             glm::vec3 colour) {
  const core::Vec3 d = b - a;
  const double length = d.norm();
  if (length < 1e-9) return;
  DrawItem rod;
  rod.shape = Shape::cylinder;
  rod.model = glm::translate(glm::mat4(1.0f), to_glm(0.5 * (a + b))) * align_z(d / length) *
              glm::scale(glm::mat4(1.0f), glm::vec3(radius, radius, 0.5f * static_cast<float>(length)));
  rod.material.colour = colour;
  items.push_back(rod);
}

}  // namespace

std::vector<components::LinkPose> tree_poses(const BodyVisual& tree, const PoseTrack& poses,
                                             int index, double t) {
  const int n = tree.tree->joint_count();
  core::Vec q(n);
  for (int i = 0; i < n; ++i) q[i] = poses.angle(index, i, t);
  return tree.tree->link_poses(q);
}

std::vector<core::Vec3> tree_points(const BodyVisual& b, const PoseTrack& poses, int index,
                                    double t) {
  const std::vector<components::LinkPose> p = tree_poses(b, poses, index, t);
  std::vector<core::Vec3> out{b.tree->params().base_position};
  for (const auto& [from, to] : rods(b, p)) {
    out.push_back(from);
    out.push_back(to);
  }
  for (const auto& v : b.visuals) {
    if (v.shape == scene::UrdfVisual::Shape::mesh) continue;
    const components::LinkPose f = visual_frame(b, p, v);
    const double r = 0.5 * v.size.norm();
    for (int k = 0; k < 8; ++k) {
      out.push_back(f.p + core::Vec3((k & 1) ? r : -r, (k & 2) ? r : -r, (k & 4) ? r : -r));
    }
  }
  return out;
}

void add_tree_items(std::vector<DrawItem>& items, const BodyVisual& b, const PoseTrack& poses,
                    int index, double t) {
  const std::vector<components::LinkPose> p = tree_poses(b, poses, index, t);
  if (!b.visuals.empty()) {
    for (const auto& v : b.visuals) {
      if (v.shape == scene::UrdfVisual::Shape::mesh) continue;  // warned by frame_renderer_for
      const components::LinkPose f = visual_frame(b, p, v);
      DrawItem item;
      glm::vec3 half(0.0f);
      switch (v.shape) {
        case scene::UrdfVisual::Shape::box:
          item.shape = Shape::box;
          half = 0.5f * to_glm(v.size);
          break;
        case scene::UrdfVisual::Shape::cylinder:
          item.shape = Shape::cylinder;
          half = glm::vec3(to_glm(v.size).x, to_glm(v.size).y, 0.5f * to_glm(v.size).z);
          break;
        case scene::UrdfVisual::Shape::sphere:
        case scene::UrdfVisual::Shape::mesh:
          item.shape = Shape::sphere;
          half = to_glm(v.size);
          break;
      }
      item.model = glm::translate(glm::mat4(1.0f), to_glm(f.p)) * to_glm(f.q) *
                   glm::scale(glm::mat4(1.0f), half);
      item.material.colour = glm::vec3(static_cast<float>(v.rgba[0]), static_cast<float>(v.rgba[1]),
                                       static_cast<float>(v.rgba[2]));
      items.push_back(item);
    }
    return;
  }
  const auto& links = b.tree->params().links;
  std::size_t k = 0;
  for (const auto& [from, to] : rods(b, p)) {
    const std::size_t link = std::min(k, links.size() - 1);
    add_rod(items, from, to, 0.5f * static_cast<float>(b.widths[link]),
            k % 2 == 0 ? kRodColour : kRodColour2);
    ++k;
  }
  for (std::size_t i = 0; i < links.size(); ++i) {
    const core::Vec3 axis = (p[i].q * links[i].axis).normalized();
    const float w = static_cast<float>(b.widths[i]);
    DrawItem pin;
    pin.shape = Shape::cylinder;
    pin.model = glm::translate(glm::mat4(1.0f), to_glm(p[i].p)) * align_z(axis) *
                glm::scale(glm::mat4(1.0f), glm::vec3(0.8f * w, 0.8f * w, 0.9f * w));
    pin.material.colour = kJointColour;
    pin.material.specular = 0.5f;
    items.push_back(pin);
  }
}

}  // namespace stiction::render
