// Psi/Phi for an element between two articulation frames (paper Simulation III, eq. 29):
// a point fixed on the child body and a point fixed on the parent body, or a fixed world
// point when the parent is the ground (nullptr).
// x_hat (26) = [child frame (13), parent frame (13)], each frame being
//   [p (3), v (3), q (w, x, y, z) (4), w_world (3)]
// in world coordinates: the point's position and velocity, the body's orientation and its
// world-frame angular velocity. The ground frame is the fixed point with identity q and zero
// velocities.
// u (6) = [f (3), torque (3)], world frame: the wrench the child side exerts on the element
// (DESIGN section 1). The child receives -f at its point plus the free torque -torque; the
// parent receives +f at its point and +torque. Both bodies must be able to rotate.
#pragma once

#include "core/body.hpp"
#include "core/coordinate_map.hpp"

namespace stiction::components {

class FramePairMap final : public core::CoordinateMap {
 public:
  static constexpr int kFrameSize = 13;

  FramePairMap(const core::Body* parent, core::Vec3 parent_local_point, const core::Body& child,
               core::Vec3 child_local_point);
  int motion_size() const override { return 2 * kFrameSize; }
  int force_size() const override { return 6; }
  // Child first, then the parent if any.
  std::vector<const core::Admittance*> admittances() const override;
  void bind(const std::vector<core::Slot>& slots) override;
  void motion(core::ConstVecRef x, core::VecRef x_hat) const override;
  void apply(core::ConstVecRef x, core::ConstVecRef u, core::VecRef u_hat) const override;

 private:
  const core::Body* parent_;
  core::Vec3 parent_local_;  // world point when parent_ is null
  const core::Body& child_;
  core::Vec3 child_local_;
  core::Slot child_slot_, parent_slot_;
};

}  // namespace stiction::components
