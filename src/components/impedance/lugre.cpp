#include "components/impedance/lugre.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace stiction::components {
namespace {

// The highest steady deflection max g: F / K, or the static level's Fs / K with Stribeck.
double bristle_bound(const LuGreParams& p) {
  const double top =
      p.stribeck_velocity > 0.0 ? std::max(p.force_limit, p.static_limit) : p.force_limit;
  return top / p.stiffness;
}

}  // namespace

LuGre::LuGre(std::string name, const LuGreParams& params)
    : core::Impedance(std::move(name)),
      FrictionSpring(params.stiffness, params.damping),
      core::BoundedState(bristle_bound(params)),
      params_(params) {
  const LuGreParams& p = params_;
  if (!(p.stiffness > 0.0) || !(p.force_limit > 0.0) || !(p.damping >= 0.0) ||
      !(p.viscous >= 0.0)) {
    throw std::invalid_argument("lugre '" + this->name() +
                                "': needs stiffness > 0, force_limit > 0, damping >= 0, "
                                "viscous >= 0");
  }
  // g(v) must stay positive: with Stribeck on, g ranges between F/K and Fs/K.
  if (p.stribeck_velocity > 0.0 && !(p.static_limit > 0.0)) {
    throw std::invalid_argument("lugre '" + this->name() +
                                "': a Stribeck velocity needs static_limit > 0");
  }
}

double LuGre::steady_deflection(double v) const {
  const LuGreParams& p = params_;
  if (p.stribeck_velocity <= 0.0) return p.force_limit / p.stiffness;
  const double s = v / p.stribeck_velocity;
  return (p.force_limit + (p.static_limit - p.force_limit) * std::exp(-s * s)) / p.stiffness;
}

void LuGre::evaluate(double /*t*/, core::ConstVecRef x_hat, core::ConstVecRef y, double /*tau*/,
                     core::VecRef u, core::VecRef y_dot) const {
  const double v = x_hat[1];
  const double e = y[0];
  const double e_dot = v - std::abs(v) * e / steady_deflection(v);
  u[0] = params_.stiffness * e + params_.damping * e_dot + params_.viscous * v;
  y_dot[0] = e_dot;
}

std::vector<core::SignalInfo> LuGre::signals() const {
  return {{.name = "tau", .unit = "N·m", .frame = "joint",
           .description = "friction torque on the driven side of the joint"},
          {.name = "e", .unit = "rad", .frame = "joint",
           .description = "bristle deflection (internal state z)"}};
}

void LuGre::write_signals(core::ConstVecRef /*x_hat*/, core::ConstVecRef y, core::ConstVecRef u,
                          core::VecRef out) const {
  out[0] = -u[0];  // on the driven side
  out[1] = y[0];
}

}  // namespace stiction::components
