#include "components/impedance/spring_damper.hpp"

#include <stdexcept>

namespace stiction::components {

SpringDamper::SpringDamper(std::string name, const SpringDamperParams& params)
    : core::Impedance(std::move(name)),
      core::StiffnessHint(params.stiffness, params.damping),
      params_(params) {
  const int n = params_.dimension;
  if (n < 1) throw std::invalid_argument("spring_damper '" + this->name() + "': dimension < 1");
  if (!(params_.stiffness >= 0.0) || !(params_.damping >= 0.0)) {
    throw std::invalid_argument("spring_damper '" + this->name() +
                                "': stiffness and damping must be >= 0");
  }
  if (params_.rest.size() == 0) params_.rest = core::Vec::Zero(n);
  if (params_.rest.size() != n) {
    throw std::invalid_argument("spring_damper '" + this->name() + "': rest must have " +
                                std::to_string(n) + " entries");
  }
}

void SpringDamper::evaluate(double /*t*/, core::ConstVecRef x_hat, core::ConstVecRef /*y*/,
                            double /*tau*/, core::VecRef u, core::VecRef /*y_dot*/) const {
  const int n = params_.dimension;
  u = params_.stiffness * (x_hat.head(n) - params_.rest) + params_.damping * x_hat.tail(n);
}

double SpringDamper::stored_energy(core::ConstVecRef x_hat, core::ConstVecRef /*y*/) const {
  return 0.5 * params_.stiffness * (x_hat.head(params_.dimension) - params_.rest).squaredNorm();
}

std::vector<core::SignalInfo> SpringDamper::signals() const {
  const int n = params_.dimension;
  if (n == 1) {
    return {{.name = "tau", .unit = "N·m", .frame = "joint",
             .description = "spring-damper torque on the driven side of the joint"}};
  }
  return {{.name = "f", .axes = n == 3 ? core::xyz_axes() : core::index_axes(n), .unit = "N",
           .frame = "world", .description = "spring-damper force on the moving point"}};
}

void SpringDamper::write_signals(core::ConstVecRef /*x_hat*/, core::ConstVecRef /*y*/,
                                 core::ConstVecRef u, core::VecRef out) const {
  out = -u;  // the force on the moving side
}

}  // namespace stiction::components
