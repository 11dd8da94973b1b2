// Geometry shared by the files that turn a scene description into draw items, bounds and
// framing points: tangent bases, rotations, an arm's pose, the joints' world points.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "core/types.hpp"
#include "render/scene_view.hpp"

namespace stiction::render {

// Tangent basis of a surface: t1 along x where possible (down the slope of a tilted plane).
void tangents(const core::Vec3& n, core::Vec3& t1, core::Vec3& t2);

glm::mat4 rotation_from_basis(const core::Vec3& x, const core::Vec3& y, const core::Vec3& z);

glm::mat4 to_glm(const core::Quat& q);

struct ArmPose {
  std::vector<core::Vec3> joints;  // n + 1 points: joints then the tip
  std::vector<double> phi;         // absolute angle of each link
};

ArmPose arm_pose(const BodyVisual& arm, const PoseTrack& poses, int index, double t);

// True if body `index` is a child or a parent of a joint: a link, drawn as an arm's link is.
bool is_link(const Drawing& scene, int index);

// Rotation taking the unit shapes' z axis to `axis` (unit).
glm::mat4 align_z(const core::Vec3& axis);

// World position of a joint's articulation point and world direction of its axis, both from
// the child's pose (the parent's point differs by the joint's tiny separation).
core::Vec3 joint_point(const JointVisual& j, const PoseTrack& poses, double t);
core::Vec3 joint_axis(const JointVisual& j, const PoseTrack& poses, double t);

// Half-extents of the axis-aligned box around a box of full sides `size` turned by `q`.
glm::vec3 box_half_extent(const core::Vec3& size, const core::Quat& q);

// Characteristic size of the scene's bodies: sets the checker square.
double body_scale(const Drawing& scene);

// A body's size as drawn: a sphere's diameter, a box's or block's largest side, an arm's
// widest link. Sets the size of what is drawn on it (coils, arrows).
double piece_size(const BodyVisual& body);

// Height of the floor drawn under a scene without contact surfaces: below the lowest point
// of the bodies over the run (`all`), three link widths under an arm, half `scale` else.
double floor_height(const Drawing& scene, const Bounds& all, double scale);

}  // namespace stiction::render
