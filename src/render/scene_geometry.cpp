#include "render/scene_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>

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

bool is_link(const SceneDescription& scene, int index) {
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

}  // namespace stiction::render
