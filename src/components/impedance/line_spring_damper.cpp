#include "components/impedance/line_spring_damper.hpp"

#include <stdexcept>

namespace stiction::components {

LineSpringDamper::LineSpringDamper(std::string name, const LineSpringDamperParams& params)
    : core::Impedance(std::move(name)),
      core::StiffnessHint(params.stiffness, params.damping),
      params_(params) {
  if (!(params_.stiffness >= 0.0) || !(params_.damping >= 0.0) || !(params_.length >= 0.0)) {
    throw std::invalid_argument("spring_damper '" + this->name() +
                                "': stiffness, damping and length must be >= 0");
  }
}

void LineSpringDamper::evaluate(double /*t*/, core::ConstVecRef x_hat, core::ConstVecRef /*y*/,
                                double /*tau*/, core::VecRef u, core::VecRef /*y_dot*/) const {
  const core::Vec3 d = x_hat.head<3>();
  const double length = d.norm();
  if (!(length > 0.0)) {
    u.setZero();
    return;
  }
  const core::Vec3 n = d / length;
  const double rate = n.dot(x_hat.segment<3>(3));
  u = (params_.stiffness * (length - params_.length) + params_.damping * rate) * n;
}

double LineSpringDamper::stored_energy(core::ConstVecRef x_hat, core::ConstVecRef /*y*/) const {
  const double stretch = x_hat.head<3>().norm() - params_.length;
  return 0.5 * params_.stiffness * stretch * stretch;
}

std::vector<core::SignalInfo> LineSpringDamper::signals() const {
  return {{"f", core::xyz_axes()}, {"length", {}}};
}

void LineSpringDamper::write_signals(core::ConstVecRef x_hat, core::ConstVecRef /*y*/,
                                     core::ConstVecRef u, core::VecRef out) const {
  out.head<3>() = -u;  // the force on the moving side
  out[3] = x_hat.head<3>().norm();
}

}  // namespace stiction::components
