// Psi/Phi for a contact against a moving surface (moving_contact.hpp): x_hat = [p_b (3),
// v_b (3), w (3), s (1)], the world position and velocity of the body-frame point `local`,
// the body's world angular velocity, and the time s from a Clock admittance. The body
// receives -u[0:3] at the point and the free torque -u[3:6]; the clock receives nothing.
#pragma once

#include "core/body.hpp"
#include "core/coordinate_map.hpp"

namespace stiction::components {

class SurfacePointMap final : public core::CoordinateMap {
 public:
  SurfacePointMap(const core::Body& body, const core::Vec3& local, const core::Admittance& clock)
      : body_(body), local_(local), clock_(clock) {}
  int motion_size() const override { return 10; }
  int force_size() const override { return 6; }
  // [v_b, w] for [force, torque]: the body's side (the surface moves by the clock alone).
  int conjugate_velocity_offset() const override { return 3; }
  std::vector<const core::Admittance*> admittances() const override { return {&body_, &clock_}; }
  void bind(const std::vector<core::Slot>& slots) override {
    body_slot_ = slots.at(0);
    clock_slot_ = slots.at(1);
  }
  void motion(core::ConstVecRef x, core::VecRef x_hat) const override {
    const core::BodyMotion m =
        body_.motion(x.segment(body_slot_.state_offset, body_slot_.state_size));
    const core::Vec3 lever = m.q * local_;
    x_hat.segment<3>(0) = m.p + lever;
    x_hat.segment<3>(3) = m.v + m.w_world.cross(lever);
    x_hat.segment<3>(6) = m.w_world;
    x_hat[9] = x[clock_slot_.state_offset];
  }
  void apply(core::ConstVecRef x, core::ConstVecRef u, core::VecRef u_hat) const override {
    const core::BodyMotion m =
        body_.motion(x.segment(body_slot_.state_offset, body_slot_.state_size));
    body_.add_wrench(m, m.q * local_, -core::Vec3(u.head<3>()), -core::Vec3(u.segment<3>(3)),
                     u_hat.segment(body_slot_.input_offset, body_slot_.input_size));
  }

 private:
  const core::Body& body_;
  core::Vec3 local_;
  const core::Admittance& clock_;
  core::Slot body_slot_, clock_slot_;
};

}  // namespace stiction::components
