// Rigid body with a unit quaternion (paper eqs. 25-26): state [p, v, q, w] (13) with
// q = (w, x, y, z) body-to-world and w the angular velocity in the body frame; input
// [f (world), tau (body frame)] (6). q_dot = 0.5 q (x) (0, w), w_dot = J^-1 (tau - w x J w).
// q is renormalized after each step (project), never inside the derivative.
// Signals p, v, q, w (w in the body frame, as in the state).
#pragma once

#include "core/body.hpp"

namespace stiction::components {

struct RigidBodyParams {
  double mass = 1.0;
  core::Mat3 inertia = core::Mat3::Identity();  // body frame, about the centre of mass
  core::Vec3 position = core::Vec3::Zero();
  core::Vec3 velocity = core::Vec3::Zero();
  core::Quat orientation = core::Quat::Identity();
  core::Vec3 angular_velocity = core::Vec3::Zero();  // body frame
  core::Vec3 gravity{0.0, 0.0, -9.8};
};

class RigidBody final : public core::Body {
 public:
  RigidBody(std::string name, const RigidBodyParams& params);
  std::string_view type() const override { return "rigid_body"; }
  int state_size() const override { return 13; }
  int input_size() const override { return 6; }
  std::vector<std::string> state_labels() const override;
  void initial_state(core::VecRef x) const override;
  void derivative(core::ConstVecRef x, core::ConstVecRef u_hat, core::VecRef x_dot) const override {
    derivative_at(x.data(), u_hat.data(), x_dot.data());
  }
  bool affine_in_input() const override { return true; }
  void derivative_at(const double* x, const double* u_hat, double* x_dot) const override;
  void project(core::VecRef x) const override;
  void solve_kinematics(const double* start, double* iterate, double h) const override;
  std::vector<core::SignalInfo> signals() const override;
  void write_signals(core::ConstVecRef x, core::VecRef out) const override;
  double energy(core::ConstVecRef x) const override;

  // Inline: contact couplings fuse them into their straight code (core/coupling.hpp).
  core::BodyMotion motion(core::ConstVecRef x) const override {
    core::BodyMotion m;
    m.p = x.segment<3>(0);
    m.v = x.segment<3>(3);
    // Stage states are not renormalized (the derivative must stay plain vector
    // arithmetic), so use the normalized rotation for kinematics.
    m.q = orientation(x);
    m.w_world = m.q * core::Vec3(x.segment<3>(10));
    return m;
  }
  void add_wrench(const core::BodyMotion& at, const core::Vec3& lever, const core::Vec3& force,
                  const core::Vec3& torque, core::VecRef u_hat) const override {
    u_hat.segment<3>(0) += force;
    u_hat.segment<3>(3) += at.q.conjugate() * (lever.cross(force) + torque);
  }
  bool can_rotate() const override { return true; }
  const RigidBodyParams& params() const { return params_; }
  // Where the body starts (scene loading: a contact's `settle` moves it into equilibrium).
  void set_initial_pose(const core::Vec3& p, const core::Quat& q) {
    params_.position = p;
    params_.orientation = q.normalized();
  }

 private:
  static core::Quat orientation(core::ConstVecRef x) {
    return core::Quat(x[6], x[7], x[8], x[9]).normalized();
  }

  RigidBodyParams params_;
  core::Mat3 inertia_inverse_;
  // Principal-axis bodies (spheres, boxes) skip the 3x3 products in the hot path.
  bool diagonal_inertia_ = false;
  core::Vec3 inertia_diagonal_;
};

}  // namespace stiction::components
