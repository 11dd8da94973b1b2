// Psi/Phi for a contact against a flat surface of normal n: the contact point of a body of
// round shape `radius` is its point nearest the surface, p - radius n (radius 0: the body
// origin, e.g. a point mass). x_hat = [p_c (3), v_c (3)] with v_c = v + w x (p_c - p);
// the body receives -u at p_c (force and the matching torque).
#pragma once

#include "core/body.hpp"
#include "core/coordinate_map.hpp"

namespace stiction::components {

class ContactPointMap final : public core::CoordinateMap {
 public:
  ContactPointMap(const core::Body& body, double radius, const core::Vec3& normal);
  int motion_size() const override { return 6; }
  int force_size() const override { return 3; }
  std::vector<const core::Admittance*> admittances() const override { return {&body_}; }
  void bind(const std::vector<core::Slot>& slots) override { slot_ = slots.at(0); }
  void motion(core::ConstVecRef x, core::VecRef x_hat) const override;
  void apply(core::ConstVecRef x, core::ConstVecRef u, core::VecRef u_hat) const override;

 private:
  const core::Body& body_;
  core::Vec3 offset_;  // contact point minus body origin, world frame
  core::Slot slot_;
};

}  // namespace stiction::components
