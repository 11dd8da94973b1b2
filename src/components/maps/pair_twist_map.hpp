// Psi/Phi for a rolling or spinning resistance element between two bodies
// (pair_rolling_resistance.hpp): the pair contact's input and the bodies' relative angular
// velocity. x_hat = [d (1), n (3), v_rel (3), w_rel (3)]: the first seven exactly as the
// pair's contact element receives them (the same PairContactMap computes them, so the
// element's N is that element's normal force to the last bit), then w_a - w_b (world).
// Phi applies -u to the first body and +u to the second as free torques (world): a couple,
// so the pair's angular momentum is kept.
#pragma once

#include "components/maps/pair_contact_map.hpp"
#include "core/body.hpp"
#include "core/coordinate_map.hpp"

namespace stiction::components {

class PairTwistMap final : public core::CoordinateMap {
 public:
  PairTwistMap(const core::Body& a, const core::Body& b, const PairShape& shape)
      : a_(a), b_(b), contact_(a, b, shape) {}
  int motion_size() const override { return 10; }
  int force_size() const override { return 3; }
  int conjugate_velocity_offset() const override { return 7; }  // w_a - w_b
  std::vector<const core::Admittance*> admittances() const override { return {&a_, &b_}; }
  void bind(const std::vector<core::Slot>& slots) override {
    slot_a_ = slots.at(0);
    slot_b_ = slots.at(1);
    contact_.bind(slots);
  }
  void motion(core::ConstVecRef x, core::VecRef x_hat) const override {
    contact_.motion(x, x_hat.head(7));
    x_hat.segment<3>(7) = motion_a(x).w_world - motion_b(x).w_world;
  }
  void apply(core::ConstVecRef x, core::ConstVecRef u, core::VecRef u_hat) const override {
    const core::Vec3 on_a = -u.head<3>();
    a_.add_wrench(motion_a(x), core::Vec3::Zero(), core::Vec3::Zero(), on_a,
                  u_hat.segment(slot_a_.input_offset, slot_a_.input_size));
    b_.add_wrench(motion_b(x), core::Vec3::Zero(), core::Vec3::Zero(), -on_a,
                  u_hat.segment(slot_b_.input_offset, slot_b_.input_size));
  }

 private:
  core::BodyMotion motion_a(core::ConstVecRef x) const {
    return a_.motion(x.segment(slot_a_.state_offset, slot_a_.state_size));
  }
  core::BodyMotion motion_b(core::ConstVecRef x) const {
    return b_.motion(x.segment(slot_b_.state_offset, slot_b_.state_size));
  }

  const core::Body& a_;
  const core::Body& b_;
  PairContactMap contact_;  // where the pair touches, as its contact element sees it
  core::Slot slot_a_, slot_b_;
};

}  // namespace stiction::components
