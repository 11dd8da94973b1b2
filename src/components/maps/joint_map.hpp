// Psi/Phi for a 1-D joint impedance: x_hat = [theta_i, omega_i] of one joint of a
// JointSpace admittance; the joint receives -u (u is the element's generalized force as
// exerted by the moving side, DESIGN section 1).
#pragma once

#include "core/body.hpp"
#include "core/coordinate_map.hpp"

namespace stiction::components {

class JointMap final : public core::CoordinateMap {
 public:
  JointMap(const core::JointSpace& arm, int joint) : arm_(arm), joint_(joint) {}
  int motion_size() const override { return 2; }
  int force_size() const override { return 1; }
  std::vector<const core::Admittance*> admittances() const override { return {&arm_}; }
  void bind(const std::vector<core::Slot>& slots) override { slot_ = slots.at(0); }
  void motion(core::ConstVecRef x, core::VecRef x_hat) const override;
  void apply(core::ConstVecRef x, core::ConstVecRef u, core::VecRef u_hat) const override;

 private:
  const core::JointSpace& arm_;
  int joint_;
  core::Slot slot_;
};

}  // namespace stiction::components
