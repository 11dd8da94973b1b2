// Kinematic tree of revolute and prismatic joints about any axes, in 3-D under gravity
// (the paper's eq. 8 for any n-DOF mechanism): state [q (n), qd (n)], input joint forces
// or torques tau (n). Link i hangs from joint i; its parent is link `parent` (-1: the base,
// fixed to the world at `base_position`, `base_orientation`). Parents come before children.
// Joint i's frame sits at `origin` with `rotation` in its parent link's frame (URDF's
// <origin xyz rpy>) and moves about (revolute) or along (prismatic) its unit `axis`, given
// in that joint frame; link i's frame is the joint frame after the joint's motion, and its
// mass, centre of mass and inertia (about the centre of mass) are in that frame.
// Forward dynamics by the articulated-body algorithm in O(n) (spatial_tree_aba.cpp);
// mass_matrix() (composite rigid bodies) and bias() (recursive Newton-Euler) give the same
// accelerations by a dense solve, for tests. Signals theta and omega, their axes named by
// the joints. Not thread-safe: one tree is evaluated by one thread at a time (scratch).
#pragma once

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "core/body.hpp"

namespace stiction::components {

enum class SpatialJointType { revolute, prismatic };

struct SpatialLink {
  std::string joint_name;  // the joint's name: CSV axes, `joint = "NAME"` in scenes
  std::string link_name;   // the link's name (URDF), for messages and drawing
  int parent = -1;         // index of the parent link (< this one's), -1: the base
  SpatialJointType type = SpatialJointType::revolute;
  core::Vec3 axis = core::Vec3::UnitZ();         // in the joint frame; normalized on use
  core::Vec3 origin = core::Vec3::Zero();        // joint frame origin in the parent's frame
  core::Quat rotation = core::Quat::Identity();  // joint frame in the parent's frame
  double mass = 1.0;
  core::Vec3 com = core::Vec3::Zero();              // in the link frame
  core::Mat3 inertia = core::Mat3::Identity() * 1e-3;  // about the com, link frame
  // Joint travel (rad or m); infinite: none. Enforced by the scene's limit elements.
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
};

struct SpatialTreeParams {
  std::vector<SpatialLink> links;
  core::Vec3 base_position = core::Vec3::Zero();
  core::Quat base_orientation = core::Quat::Identity();
  core::Vec angles;  // initial q (n), zero if empty
  core::Vec rates;   // initial qd (n), zero if empty
  core::Vec3 gravity = core::Vec3::Zero();  // world gravity acceleration
};

// World pose of a link frame.
struct LinkPose {
  core::Vec3 p = core::Vec3::Zero();
  core::Quat q = core::Quat::Identity();
};

class SpatialTree final : public core::JointSpace {
 public:
  SpatialTree(std::string name, const SpatialTreeParams& params);
  std::string_view type() const override { return "spatial_tree"; }
  int state_size() const override { return 2 * joint_count(); }
  int input_size() const override { return joint_count(); }
  std::vector<std::string> state_labels() const override;
  void initial_state(core::VecRef x) const override;
  void derivative(core::ConstVecRef x, core::ConstVecRef u_hat, core::VecRef x_dot) const override;
  bool affine_in_input() const override { return true; }
  std::vector<core::SignalInfo> signals() const override;
  void write_signals(core::ConstVecRef x, core::VecRef out) const override;
  // Kinetic energy plus the links' potential energy -sum m_i g . c_i.
  double energy(core::ConstVecRef x) const override;

  int joint_count() const override { return static_cast<int>(params_.links.size()); }
  double joint_angle(core::ConstVecRef x, int joint) const override { return x[joint]; }
  double joint_rate(core::ConstVecRef x, int joint) const override {
    return x[joint_count() + joint];
  }
  void add_joint_torque(int joint, double torque, core::VecRef u_hat) const override {
    u_hat[joint] += torque;
  }
  // Index of the joint named `name`, -1 if none.
  int joint_index(const std::string& name) const;
  std::string joint_name(int joint) const override { return params_.links[joint].joint_name; }

  // qdd = H^-1 (tau - c) in O(n), articulated-body algorithm.
  void forward_dynamics(core::ConstVecRef q, core::ConstVecRef qd, core::ConstVecRef tau,
                        core::VecRef qdd) const;
  // Joint-space inertia H(q) (n x n) and bias c(q, qd) (Coriolis, centrifugal, minus
  // gravity's generalized force): H qdd + c = tau.
  void mass_matrix(core::ConstVecRef q, Eigen::Ref<Eigen::MatrixXd> H) const;
  void bias(core::ConstVecRef q, core::ConstVecRef qd, core::VecRef c) const;
  // World poses of every link frame at q (n entries), for drawing and tests.
  std::vector<LinkPose> link_poses(core::ConstVecRef q) const;

  const SpatialTreeParams& params() const { return params_; }

 private:
  SpatialTreeParams params_;
  struct Scratch;  // the algorithm's per-link arrays, sized once (spatial_tree.cpp)
  std::shared_ptr<Scratch> scratch_;
};

}  // namespace stiction::components
