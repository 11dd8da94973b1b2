#include "components/impedance/kikuuwe_friction.hpp"

#include <cmath>
#include <stdexcept>

namespace stiction::components {

using core::ConstVecRef;
using core::VecRef;

void saturate(double limit, VecRef x) {
  const double norm = x.norm();
  if (norm > limit) x *= limit / norm;
}

KikuuweFriction::KikuuweFriction(std::string name, const KikuuweFrictionParams& params)
    : Impedance(std::move(name)),
      FrictionSpring(params.stiffness, params.damping),
      params_(params) {
  // Up to 3: its slip velocity is a 3-vector (a joint, a point).
  if (params_.dimension < 1 || params_.dimension > 3) {
    throw std::invalid_argument("kikuuwe friction: dimension must be 1, 2 or 3");
  }
  if (!(params_.stiffness > 0.0) || !(params_.damping >= 0.0) || !(params_.force_limit >= 0.0)) {
    throw std::invalid_argument("kikuuwe friction: need K > 0, B >= 0, F >= 0");
  }
  levels_ = {params_.force_limit,
             params_.static_limit < 0.0 ? params_.force_limit : params_.static_limit,
             params_.stribeck_velocity, params_.viscous};
  if (!(levels_.breakaway >= levels_.kinetic) || !std::isfinite(levels_.breakaway) ||
      !(levels_.stribeck_velocity >= 0.0) || !std::isfinite(levels_.stribeck_velocity) ||
      !(levels_.viscous >= 0.0) || !std::isfinite(levels_.viscous)) {
    throw std::invalid_argument(
        "kikuuwe friction: need static_limit >= force_limit, stribeck_velocity >= 0 and "
        "viscous >= 0, finite");
  }
}

std::vector<std::string> KikuuweFriction::state_labels() const {
  if (params_.dimension == 1) return {"e"};
  std::vector<std::string> labels;
  for (const auto& a : core::index_axes(params_.dimension)) labels.push_back("e." + a);
  return labels;
}

void KikuuweFriction::evaluate(double /*t*/, ConstVecRef x_hat, ConstVecRef y, double tau,
                               VecRef u, VecRef y_dot) const {
  const int n = params_.dimension;
  const double K = params_.stiffness;
  const double BtK = params_.damping + tau * K;
  const auto v = x_hat.segment(n, n);
  // (19b): f = gsat(F, (B + tau K) v + K e).
  u = BtK * v + K * y;
  const double norm = u.norm();
  if (norm <= levels_.breakaway) {
    // Not saturated: (19c) reduces to eps = v. Written as such so that it holds to the last
    // bit; (f - K e) / (B + tau K) would differ from v by rounding and let a stuck joint creep.
    y_dot = v;
  } else {
    u *= levels_.sliding_force(norm, BtK) / norm;
    y_dot = (u - K * y) / BtK;
  }
}

core::Vec3 KikuuweFriction::slip_velocity(ConstVecRef x_hat) const {
  const int n = params_.dimension;
  core::Vec3 v = core::Vec3::Zero();
  v.head(n) = x_hat.segment(n, n);
  return v;
}

std::vector<core::SignalInfo> KikuuweFriction::signals() const {
  // One dimension: a joint (torque, angle); more: a point (force, displacement).
  if (params_.dimension == 1) {
    return {{.name = "tau", .unit = "N·m", .frame = "joint",
             .description = "friction torque on the driven side of the joint"},
            {.name = "e", .unit = "rad", .frame = "joint",
             .description = "elastic displacement of the friction element (anchor offset)"}};
  }
  const auto axes = params_.dimension == 3 ? core::xyz_axes() : core::index_axes(params_.dimension);
  return {{.name = "f", .axes = axes, .unit = "N", .frame = "world",
           .description = "friction force on the moving point"},
          {.name = "e", .axes = axes, .unit = "m", .frame = "world",
           .description = "elastic displacement of the friction element"}};
}

void KikuuweFriction::write_signals(ConstVecRef /*x_hat*/, ConstVecRef y, ConstVecRef u,
                                    VecRef out) const {
  const int n = params_.dimension;
  // Friction torque/force acting on the driven side: -u (DESIGN section 1).
  out.head(n) = -u;
  out.segment(n, n) = y;
}

}  // namespace stiction::components
