// Capabilities that several friction elements implement alike, written once
// (core/capabilities.hpp):
// - JointSlip: the slip velocity of an element on one joint or slider, x_hat = [position,
//   velocity]: the velocity, in the x entry (Dahl, LuGre, a user's joint friction);
// - FrictionSpring: an element whose state y is the deflection of its friction spring K
//   (a bristle, Kikuuwe's e): it holds 0.5 K |y|^2, and K (with the damping B beside it)
//   is its stiffness for stability advice.
#pragma once

#include <limits>

#include "core/capabilities.hpp"

namespace stiction::components {

class JointSlip : public core::SlipElement {
 public:
  core::Vec3 slip_velocity(core::ConstVecRef x_hat) const override {
    return core::Vec3(x_hat[1], 0.0, 0.0);
  }
};

class FrictionSpring : public core::EnergyStore, public core::StiffnessHint {
 public:
  explicit FrictionSpring(double stiffness,
                          double damping = std::numeric_limits<double>::quiet_NaN())
      : core::StiffnessHint(stiffness, damping) {}
  double stored_energy(core::ConstVecRef /*x_hat*/, core::ConstVecRef y) const override {
    return 0.5 * stiffness() * y.squaredNorm();
  }
};

}  // namespace stiction::components
