// Psi/Phi for a rolling or spinning resistance element on a cylinder (or ring) against a
// fixed plane (rolling_resistance.hpp): the body's twist, its axis, and where its rim points
// touch, so that the element can resist the rolling about the axis and take its level from
// the load the cylinder's contacts carry.
// x_hat = [p (3), v (3), w (3), a (3), then for each rim point i = 0..kPoints-1: p_c (3),
// v_c (3)]: the body origin's world position and velocity, its world angular velocity, its
// axis in world coordinates, and each rim point's position and material velocity exactly as
// the cylinder's contact element NAME.i receives them (the same CylinderRimMap computes
// them, so the element's N is the sum of those elements' normal forces to the last bit).
// The body receives -u as a free torque (world), as from BodyTwistMap.
#pragma once

#include <array>

#include "components/maps/cylinder_rim_map.hpp"
#include "core/body.hpp"
#include "core/coordinate_map.hpp"

namespace stiction::components {

class CylinderTwistMap final : public core::CoordinateMap {
 public:
  static constexpr int kPoints = CylinderRimMap::kPoints;
  static constexpr int kAxisOffset = 9;  // where the axis is in x_hat
  static constexpr int kRimOffset = 12;  // where the rim points start in x_hat
  static constexpr int kSize = kRimOffset + 6 * kPoints;

  CylinderTwistMap(const core::Body& body, const CylinderShape& shape, const core::Vec3& normal);
  int motion_size() const override { return kSize; }
  int force_size() const override { return 3; }
  int conjugate_velocity_offset() const override { return 6; }  // w, for the torque u
  std::vector<const core::Admittance*> admittances() const override { return {&body_}; }
  void bind(const std::vector<core::Slot>& slots) override;
  void motion(core::ConstVecRef x, core::VecRef x_hat) const override;
  void apply(core::ConstVecRef x, core::ConstVecRef u, core::VecRef u_hat) const override;

 private:
  // One per rim point: CylinderRimMap alone says where a rim point is (core/rim_point.hpp).
  static std::array<CylinderRimMap, kPoints> rim_maps(const core::Body& body,
                                                      const CylinderShape& shape,
                                                      const core::Vec3& normal);

  const core::Body& body_;
  core::Vec3 axis_;  // body frame, unit
  std::array<CylinderRimMap, kPoints> rim_;
  core::Slot slot_;
};

}  // namespace stiction::components
