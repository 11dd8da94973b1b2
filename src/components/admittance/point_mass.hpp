// Point mass (paper eq. 7): state [p, v] (6), input f (3, world). Gravity is part of the
// admittance. Signals p, v. As a Body it has no orientation: torques are rejected by the
// maps that could produce them (a point mass only takes forces at its own position).
#pragma once

#include "core/body.hpp"

namespace stiction::components {

struct PointMassParams {
  double mass = 1.0;
  core::Vec3 position = core::Vec3::Zero();
  core::Vec3 velocity = core::Vec3::Zero();
  core::Vec3 gravity{0.0, 0.0, -9.8};
};

class PointMass final : public core::Body {
 public:
  PointMass(std::string name, const PointMassParams& params);
  std::string_view type() const override { return "point_mass"; }
  int state_size() const override { return 6; }
  int input_size() const override { return 3; }
  std::vector<std::string> state_labels() const override;
  void initial_state(core::VecRef x) const override;
  void derivative(core::ConstVecRef x, core::ConstVecRef u_hat, core::VecRef x_dot) const override;
  bool affine_in_input() const override { return true; }
  std::vector<core::SignalInfo> signals() const override;
  void write_signals(core::ConstVecRef x, core::VecRef out) const override;
  double energy(core::ConstVecRef x) const override;

  // Inline: contact couplings fuse them into their straight code (core/coupling.hpp).
  core::BodyMotion motion(core::ConstVecRef x) const override {
    core::BodyMotion m;
    m.p = x.segment<3>(0);
    m.v = x.segment<3>(3);
    return m;
  }
  // A point has no rotational inertia: a force acts at the point itself whatever the lever
  // arm, and a free torque has nothing to turn. Maps only attach at the origin.
  void add_wrench(const core::BodyMotion& /*at*/, const core::Vec3& /*lever*/,
                  const core::Vec3& force, const core::Vec3& /*torque*/,
                  core::VecRef u_hat) const override {
    u_hat.segment<3>(0) += force;
  }
  bool can_rotate() const override { return false; }
  const PointMassParams& params() const { return params_; }
  // Where the mass starts (scene loading: a contact's `settle` moves it into equilibrium).
  void set_initial_position(const core::Vec3& p) { params_.position = p; }

 private:
  PointMassParams params_;
};

}  // namespace stiction::components
