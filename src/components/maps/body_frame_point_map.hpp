// Psi/Phi for a 3-D element acting at a point fixed on a body, with its force expressed in
// the body's frame (a thruster, a push that turns with the body): x_hat = [R^T p_point (3),
// R^T v_point (3)] (the point's world position and velocity in body axes), and the body
// receives the world force -R u at the point. Psi and Phi are a transpose pair, so u . v
// in x_hat is the true power.
#pragma once

#include "core/body.hpp"
#include "core/coordinate_map.hpp"

namespace stiction::components {

class BodyFramePointMap final : public core::CoordinateMap {
 public:
  BodyFramePointMap(const core::Body& body, const core::Vec3& local) : body_(body), local_(local) {}
  int motion_size() const override { return 6; }
  int force_size() const override { return 3; }
  std::vector<const core::Admittance*> admittances() const override { return {&body_}; }
  void bind(const std::vector<core::Slot>& slots) override { slot_ = slots.at(0); }
  void motion(core::ConstVecRef x, core::VecRef x_hat) const override;
  void apply(core::ConstVecRef x, core::ConstVecRef u, core::VecRef u_hat) const override;

 private:
  const core::Body& body_;
  core::Vec3 local_;
  core::Slot slot_;
};

}  // namespace stiction::components
