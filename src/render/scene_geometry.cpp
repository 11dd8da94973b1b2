#include "render/scene_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <limits>

namespace stiction::render {

void tangents(const core::Vec3& n, core::Vec3& t1, core::Vec3& t2) {
  core::Vec3 a = std::abs(n.x()) < 0.9 ? core::Vec3::UnitX() : core::Vec3::UnitY();
  t1 = (a - a.dot(n) * n).normalized();
  t2 = n.cross(t1);
}

glm::mat4 rotation_from_basis(const core::Vec3& x, const core::Vec3& y, const core::Vec3& z) {
  glm::mat4 m(1.0f);
  m[0] = glm::vec4(to_glm(x), 0.0f);
  m[1] = glm::vec4(to_glm(y), 0.0f);
  m[2] = glm::vec4(to_glm(z), 0.0f);
  return m;
}

glm::mat4 to_glm(const core::Quat& q) {
  return glm::mat4_cast(glm::quat(static_cast<float>(q.w()), static_cast<float>(q.x()),
                                  static_cast<float>(q.y()), static_cast<float>(q.z())));
}

ArmPose arm_pose(const BodyVisual& arm, const PoseTrack& poses, int index, double t) {
  ArmPose pose;
  core::Vec3 p = arm.base;
  double phi = 0.0;
  pose.joints.push_back(p);
  for (std::size_t i = 0; i < arm.lengths.size(); ++i) {
    phi += poses.angle(index, static_cast<int>(i), t);
    p += arm.lengths[i] * (std::cos(phi) * arm.plane_x + std::sin(phi) * arm.plane_y);
    pose.joints.push_back(p);
    pose.phi.push_back(phi);
  }
  return pose;
}

bool is_link(const Drawing& scene, int index) {
  return std::any_of(scene.joints.begin(), scene.joints.end(),
                     [&](const JointVisual& j) { return j.child == index || j.parent == index; });
}

glm::mat4 align_z(const core::Vec3& axis) {
  core::Vec3 t1, t2;
  tangents(axis, t1, t2);
  return rotation_from_basis(t1, t2, axis);
}

core::Vec3 joint_point(const JointVisual& j, const PoseTrack& poses, double t) {
  return poses.position(j.child, t) + poses.orientation(j.child, t) * j.point;
}
core::Vec3 joint_axis(const JointVisual& j, const PoseTrack& poses, double t) {
  return (poses.orientation(j.child, t) * j.axis).normalized();
}

glm::vec3 box_half_extent(const core::Vec3& size, const core::Quat& q) {
  const core::Mat3 r = q.toRotationMatrix();
  const core::Vec3 e = r.cwiseAbs() * (0.5 * size);
  return {static_cast<float>(e.x()), static_cast<float>(e.y()), static_cast<float>(e.z())};
}

double body_scale(const Drawing& scene) {
  double s = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyVisual& b = scene.bodies[i];
    switch (b.kind) {
      case BodyVisual::Kind::sphere:
        s = std::min(s, b.radius);
        break;
      case BodyVisual::Kind::cylinder:
      case BodyVisual::Kind::box:
        // A jointed link counts as an arm's link does: half its length.
        s = std::min(s, (is_link(scene, static_cast<int>(i)) ? 0.5 : 1.0) * b.size.maxCoeff());
        break;
      case BodyVisual::Kind::block:
        s = std::min(s, b.size.maxCoeff());
        break;
      case BodyVisual::Kind::arm:
      case BodyVisual::Kind::tree:
        for (double l : b.lengths) s = std::min(s, 0.5 * l);
        break;
    }
  }
  return std::isfinite(s) ? s : 0.2;
}

double piece_size(const BodyVisual& b) {
  switch (b.kind) {
    case BodyVisual::Kind::sphere:
      return 2.0 * b.radius;
    case BodyVisual::Kind::cylinder:
    case BodyVisual::Kind::box:
    case BodyVisual::Kind::block:
      return b.size.maxCoeff();
    case BodyVisual::Kind::arm:
    case BodyVisual::Kind::tree:
      return *std::max_element(b.widths.begin(), b.widths.end());
  }
  return 0.1;
}

double floor_height(const Drawing& scene, const Bounds& all, double scale) {
  double gap = 0.5 * scale;
  // Arms and jointed rigid bodies: three link widths below the lowest joint.
  double link_width = 0.0;
  for (const auto& b : scene.bodies) {
    if (jointed(b)) {
      link_width = std::max(link_width, *std::max_element(b.widths.begin(), b.widths.end()));
    }
  }
  for (const auto& j : scene.joints) link_width = std::max(link_width, j.width);
  if (link_width > 0.0) gap = 3.0 * link_width;
  return (all.empty() ? 0.0 : all.min.z) - gap;
}

}  // namespace stiction::render
