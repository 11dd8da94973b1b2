// Psi/Phi for a 1-D element acting about an axis between two rigid bodies (or a body and
// the ground): a motor on a penalty joint (Simulation III). The axis is fixed in the child
// body's frame. x_hat = [relative angle about the axis (the twist of q_parent^-1 q_child),
// relative angular rate about it]; the child receives the torque -u about the axis and the
// parent its reaction +u (DESIGN section 1: u is what the moving side exerts on the element).
#pragma once

#include "core/body.hpp"
#include "core/coordinate_map.hpp"

namespace stiction::scene {

class AxisTorqueMap final : public core::CoordinateMap {
 public:
  // parent == nullptr: the ground.
  AxisTorqueMap(const core::Body& child, const core::Body* parent, const core::Vec3& axis_local);
  int motion_size() const override { return 2; }
  int force_size() const override { return 1; }
  std::vector<const core::Admittance*> admittances() const override;
  void bind(const std::vector<core::Slot>& slots) override;
  void motion(core::ConstVecRef x, core::VecRef x_hat) const override;
  void apply(core::ConstVecRef x, core::ConstVecRef u, core::VecRef u_hat) const override;

 private:
  const core::Body& child_;
  const core::Body* parent_;
  core::Vec3 axis_;  // unit, child frame
  core::Slot child_slot_, parent_slot_;
};

}  // namespace stiction::scene
