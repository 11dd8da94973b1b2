#include "viscous_coulomb_joint.hpp"

#include <algorithm>
#include <stdexcept>

namespace example {

ViscousCoulombJoint::ViscousCoulombJoint(std::string name, const ViscousCoulombParams& params)
    : Impedance(std::move(name)), StiffnessHint(params.stiffness), params_(params) {
  if (!(params.stiffness > 0.0 && params.damping >= 0.0 && params.coulomb >= 0.0 && params.viscous >= 0.0)) {
    throw std::invalid_argument("viscous_coulomb_joint: K > 0 and B, F, b >= 0 required");
  }
}

void ViscousCoulombJoint::evaluate(double, stiction::core::ConstVecRef x_hat, stiction::core::ConstVecRef y,
                                   double tau, stiction::core::VecRef u, stiction::core::VecRef y_dot) const {
  const double v = x_hat[1];
  const double e = y[0];
  const double K = params_.stiffness;
  const double BK = params_.damping + tau * K;
  const double coulomb = std::clamp(BK * v + K * e, -params_.coulomb, params_.coulomb);
  y_dot[0] = (coulomb - K * e) / BK;
  u[0] = coulomb + params_.viscous * v;
}

std::vector<stiction::core::SignalInfo> ViscousCoulombJoint::signals() const {
  stiction::core::SignalInfo torque;
  torque.name = "tau";  // the torque on the joint, -u
  stiction::core::SignalInfo e;
  e.name = "e";
  return {torque, e};
}

void ViscousCoulombJoint::write_signals(stiction::core::ConstVecRef, stiction::core::ConstVecRef y,
                                        stiction::core::ConstVecRef u, stiction::core::VecRef out) const {
  out[0] = -u[0];
  out[1] = y[0];
}

}  // namespace example
