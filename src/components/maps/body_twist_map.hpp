// Psi/Phi for an element on a body's rotation (rolling_resistance.hpp): x_hat = [p (3), v (3),
// w (3)], the body origin's world position and velocity and the body's world angular velocity
// (its twist, with the position the element needs to find its contact). The body receives -u
// as a free torque (world): no force, so its centre is not pushed.
#pragma once

#include "core/body.hpp"
#include "core/coordinate_map.hpp"

namespace stiction::components {

class BodyTwistMap final : public core::CoordinateMap {
 public:
  explicit BodyTwistMap(const core::Body& body) : body_(body) {}
  int motion_size() const override { return 9; }
  int force_size() const override { return 3; }
  int conjugate_velocity_offset() const override { return 6; }  // w, for the torque u
  std::vector<const core::Admittance*> admittances() const override { return {&body_}; }
  void bind(const std::vector<core::Slot>& slots) override { slot_ = slots.at(0); }
  void motion(core::ConstVecRef x, core::VecRef x_hat) const override {
    const core::BodyMotion m = body_.motion(x.segment(slot_.state_offset, slot_.state_size));
    x_hat.segment<3>(0) = m.p;
    x_hat.segment<3>(3) = m.v;
    x_hat.segment<3>(6) = m.w_world;
  }
  void apply(core::ConstVecRef x, core::ConstVecRef u, core::VecRef u_hat) const override {
    const core::BodyMotion m = body_.motion(x.segment(slot_.state_offset, slot_.state_size));
    body_.add_wrench(m, core::Vec3::Zero(), core::Vec3::Zero(), -core::Vec3(u.head<3>()),
                     u_hat.segment(slot_.input_offset, slot_.input_size));
  }

 private:
  const core::Body& body_;
  core::Slot slot_;
};

}  // namespace stiction::components
