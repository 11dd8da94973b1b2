// Psi/Phi for an element between a point fixed on body A and a point fixed on body B or in
// the world: x_hat = [p_A - p_B (3), v_A - v_B (3)] in world coordinates. A (the moving
// side) receives -u at its point, B receives +u at its point.
#pragma once

#include "core/body.hpp"
#include "core/coordinate_map.hpp"

namespace stiction::components {

class PointMap final : public core::CoordinateMap {
 public:
  // local_a, local_b: points in the bodies' frames; with b == nullptr, local_b is a fixed
  // world point.
  PointMap(const core::Body& a, core::Vec3 local_a, const core::Body* b, core::Vec3 local_b);
  int motion_size() const override { return 6; }
  int force_size() const override { return 3; }
  std::vector<const core::Admittance*> admittances() const override;
  void bind(const std::vector<core::Slot>& slots) override;
  void motion(core::ConstVecRef x, core::VecRef x_hat) const override;
  void apply(core::ConstVecRef x, core::ConstVecRef u, core::VecRef u_hat) const override;

 private:
  const core::Body& a_;
  core::Vec3 local_a_;
  const core::Body* b_;
  core::Vec3 local_b_;
  core::Slot slot_a_, slot_b_;
};

}  // namespace stiction::components
