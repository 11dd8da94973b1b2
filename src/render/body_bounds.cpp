// Where the bodies are: an arm's joints, the bodies' bounds at a time and over the run.
#include <algorithm>

#include "render/scene_geometry.hpp"
#include "render/scene_view.hpp"
#include "render/tree_items.hpp"

namespace stiction::render {

std::vector<core::Vec3> arm_joints(const BodyVisual& arm, const PoseTrack& poses, int index,
                                   double t) {
  return arm_pose(arm, poses, index, t).joints;
}

Bounds body_bounds(const Drawing& scene, const PoseTrack& poses, double t) {
  Bounds bounds;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyVisual& b = scene.bodies[i];
    const int index = static_cast<int>(i);
    if (b.kind == BodyVisual::Kind::tree) {
      const double w = *std::max_element(b.widths.begin(), b.widths.end());
      for (const auto& p : tree_points(b, poses, index, t)) {
        bounds.add(to_glm(p) - glm::vec3(float(w)));
        bounds.add(to_glm(p) + glm::vec3(float(w)));
      }
      continue;
    }
    if (b.kind == BodyVisual::Kind::arm) {
      const double w = *std::max_element(b.widths.begin(), b.widths.end());
      for (const auto& p : arm_pose(b, poses, index, t).joints) {
        bounds.add(to_glm(p) - glm::vec3(float(w)));
        bounds.add(to_glm(p) + glm::vec3(float(w)));
      }
      continue;
    }
    const glm::vec3 p = to_glm(poses.position(index, t));
    glm::vec3 r(0.0f);
    switch (b.kind) {
      case BodyVisual::Kind::sphere:
        r = glm::vec3(static_cast<float>(b.radius));
        break;
      case BodyVisual::Kind::cylinder:
      case BodyVisual::Kind::box:
        r = box_half_extent(b.size, poses.orientation(index, t));
        break;
      default:
        r = glm::vec3(static_cast<float>(b.size.norm()));
        break;
    }
    bounds.add(p - r);
    bounds.add(p + r);
  }
  // Joint cylinders, as an arm's joints.
  for (const auto& j : scene.joints) {
    const glm::vec3 p = to_glm(joint_point(j, poses, t));
    bounds.add(p - glm::vec3(static_cast<float>(j.width)));
    bounds.add(p + glm::vec3(static_cast<float>(j.width)));
  }
  return bounds;
}

Bounds run_bounds(const Drawing& scene, const PoseTrack& poses, int samples) {
  Bounds bounds;
  for (int i = 0; i < samples; ++i) {
    const double t =
        poses.start_time() + (poses.end_time() - poses.start_time()) * i / std::max(1, samples - 1);
    bounds.add(body_bounds(scene, poses, t));
  }
  return bounds;
}

}  // namespace stiction::render
