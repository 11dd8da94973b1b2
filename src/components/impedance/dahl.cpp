#include "components/impedance/dahl.hpp"

#include <cmath>
#include <stdexcept>

namespace stiction::components {

Dahl::Dahl(std::string name, const DahlParams& params)
    : core::Impedance(std::move(name)),
      FrictionSpring(params.stiffness),
      core::BoundedState(params.force_limit / params.stiffness),
      params_(params) {
  if (!(params_.stiffness > 0.0) || !(params_.force_limit > 0.0)) {
    throw std::invalid_argument("dahl '" + this->name() +
                                "': stiffness and force_limit must be > 0");
  }
}

void Dahl::evaluate(double /*t*/, core::ConstVecRef x_hat, core::ConstVecRef y, double /*tau*/,
                    core::VecRef u, core::VecRef y_dot) const {
  const double v = x_hat[1];
  const double e = y[0];
  const double K = params_.stiffness;
  u[0] = K * e;
  y_dot[0] = v - std::abs(v) * K * e / params_.force_limit;
}

std::vector<core::SignalInfo> Dahl::signals() const {
  return {{.name = "tau", .unit = "N·m", .frame = "joint",
           .description = "friction torque on the driven side of the joint"},
          {.name = "e", .unit = "rad", .frame = "joint",
           .description = "bristle deflection (internal state z)"}};
}

void Dahl::write_signals(core::ConstVecRef /*x_hat*/, core::ConstVecRef y, core::ConstVecRef u,
                         core::VecRef out) const {
  out[0] = -u[0];  // on the driven side
  out[1] = y[0];
}

}  // namespace stiction::components
