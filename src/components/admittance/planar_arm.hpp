// Planar serial arm of n revolute joints (paper eq. 8): state [theta, omega] (2n), input
// joint torques tau (n). Joint axes are parallel to `axis` (default the world z axis)
// through `base`; the arm moves in the plane through `base` normal to it. Joint i sits at
// the base end of link i and theta_i is measured relative to link i-1, positive about
// `axis` (right hand); theta_0 from the plane's first direction e1 (plane_axes()).
// H(theta) omega_dot + c(theta, omega) = tau, where c holds the Coriolis and centrifugal
// terms minus the generalized gravity force (the component of gravity in the plane; the
// part along the axis is carried by the joints' bearings).
// Signals theta, omega (axes 0..n-1). energy() is the kinetic energy 0.5 omega^T H omega
// plus the links' potential energy -sum m_i g . C_i (zero work from gravity when the plane
// is horizontal).
// Not thread-safe: derivative() and dynamics() work in preallocated mutable scratch so that
// no step allocates; one arm is evaluated by one thread at a time.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/body.hpp"

namespace stiction::components {

struct ArmLink {
  double length = 0.2;   // joint to joint (m)
  double mass = 0.2;     // kg
  double com = 0.1;      // distance of the centre of mass from the link's joint (m)
  double inertia = 0.0;  // about the centre of mass, about the joint axis (kg m^2)
};

// A uniform box link: com at the middle, I = m (length^2 + width^2) / 12.
ArmLink box_link(double length, double width, double mass);

struct PlanarArmParams {
  std::vector<ArmLink> links;
  core::Vec3 base = core::Vec3::Zero();
  core::Vec angles;  // initial theta (n), zero if empty
  core::Vec rates;   // initial omega (n), zero if empty
  core::Vec3 axis = core::Vec3::UnitZ();    // joint axis direction (world), normalized on use
  core::Vec3 gravity = core::Vec3::Zero();  // world gravity acceleration
};

// The plane of an arm with joint axis `axis` (unit): e1 is world x projected onto the plane
// (world y when the axis is along x), e2 = axis x e1, so (e1, e2, axis) is right-handed.
void arm_plane(const core::Vec3& axis, core::Vec3& e1, core::Vec3& e2);

class PlanarArm final : public core::JointSpace {
 public:
  PlanarArm(std::string name, const PlanarArmParams& params);
  std::string_view type() const override { return "planar_arm"; }
  int state_size() const override { return 2 * joint_count(); }
  int input_size() const override { return joint_count(); }
  std::vector<std::string> state_labels() const override;
  void initial_state(core::VecRef x) const override;
  void derivative(core::ConstVecRef x, core::ConstVecRef u_hat, core::VecRef x_dot) const override;
  bool affine_in_input() const override { return true; }
  std::vector<core::SignalInfo> signals() const override;
  void write_signals(core::ConstVecRef x, core::VecRef out) const override;
  double energy(core::ConstVecRef x) const override;

  int joint_count() const override { return static_cast<int>(params_.links.size()); }
  double joint_angle(core::ConstVecRef x, int joint) const override { return x[joint]; }
  double joint_rate(core::ConstVecRef x, int joint) const override {
    return x[joint_count() + joint];
  }
  void add_joint_torque(int joint, double torque, core::VecRef u_hat) const override {
    u_hat[joint] += torque;
  }

  // Joint accelerations H^-1 (tau - c) in O(n) by the articulated-body algorithm
  // (planar_arm_aba.cpp); derivative() uses it. Same results, to rounding, as solving with
  // dynamics() (tested).
  void forward_dynamics(core::ConstVecRef theta, core::ConstVecRef omega, core::ConstVecRef tau,
                        core::VecRef qdd) const;
  // 0.5 omega^T H omega in O(n), from the links' velocities.
  double kinetic_energy(core::ConstVecRef theta, core::ConstVecRef omega) const;

  // Inertia matrix H(theta) and Coriolis/centrifugal vector c(theta, omega) (eq. 8).
  void dynamics(core::ConstVecRef theta, core::ConstVecRef omega, Eigen::Ref<Eigen::MatrixXd> H,
                core::VecRef c) const;
  const PlanarArmParams& params() const { return params_; }
  // World point of plane coordinates (x, y): base + x e1 + y e2.
  core::Vec3 world_point(double x, double y) const { return params_.base + x * e1_ + y * e2_; }
  const core::Vec3& plane_x() const { return e1_; }
  const core::Vec3& plane_y() const { return e2_; }

 private:
  PlanarArmParams params_;
  core::Vec3 e1_, e2_;       // the plane (see arm_plane)
  Eigen::Vector2d g_plane_;  // gravity in plane coordinates
  // Scratch for dynamics(), sized once in the constructor.
  mutable Eigen::Matrix2Xd joints_;  // joint positions P_0..P_{n-1} in the plane
  mutable Eigen::Matrix2Xd coms_;    // centre-of-mass positions C_0..C_{n-1}
  mutable Eigen::Matrix2Xd accel_;   // C_i acceleration at zero joint acceleration
  // Scratch of the articulated-body algorithm, one entry per link.
  struct AbaScratch {
    std::vector<Eigen::Vector3d> S, c, pA, U;
    std::vector<Eigen::Matrix3d> IA;
    std::vector<double> D, u;
  };
  mutable AbaScratch aba_;
};

}  // namespace stiction::components
