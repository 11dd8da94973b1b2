#include "components/impedance/joint_limit.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace stiction::components {

JointLimit::JointLimit(std::string name, const JointLimitParams& params)
    : core::Impedance(std::move(name)),
      core::StiffnessHint(params.stiffness, params.damping),
      params_(params) {
  if (!(params_.stiffness > 0.0) || !std::isfinite(params_.stiffness) ||
      !(params_.damping >= 0.0) || !std::isfinite(params_.damping)) {
    throw std::invalid_argument("joint_limit '" + this->name() +
                                "': stiffness must be > 0 and damping >= 0 (finite)");
  }
  if (std::isnan(params_.lower) || std::isnan(params_.upper) || !(params_.lower <= params_.upper)) {
    throw std::invalid_argument("joint_limit '" + this->name() + "': needs lower <= upper");
  }
}

double JointLimit::penetration(double q) const {
  if (q > params_.upper) return q - params_.upper;
  if (q < params_.lower) return q - params_.lower;
  return 0.0;
}

void JointLimit::evaluate(double /*t*/, core::ConstVecRef x_hat, core::ConstVecRef /*y*/,
                          double /*tau*/, core::VecRef u, core::VecRef /*y_dot*/) const {
  const double d = penetration(x_hat[0]);
  if (d == 0.0) {
    u[0] = 0.0;
    return;
  }
  const double push = params_.stiffness * d + params_.damping * x_hat[1];
  // Never pull the joint into the stop: above the upper limit u >= 0, below the lower u <= 0.
  u[0] = d > 0.0 ? std::max(push, 0.0) : std::min(push, 0.0);
}

double JointLimit::stored_energy(core::ConstVecRef x_hat, core::ConstVecRef /*y*/) const {
  const double d = penetration(x_hat[0]);
  return 0.5 * params_.stiffness * d * d;
}

std::vector<core::SignalInfo> JointLimit::signals() const {
  return {{.name = "tau", .unit = "N·m", .frame = "joint",
           .description = "joint limit's torque on the joint (zero inside the travel)"}};
}

void JointLimit::write_signals(core::ConstVecRef /*x_hat*/, core::ConstVecRef /*y*/,
                               core::ConstVecRef u, core::VecRef out) const {
  out = -u;
}

}  // namespace stiction::components
