#include "components/admittance/point_mass.hpp"

#include <stdexcept>

namespace stiction::components {

using core::ConstVecRef;
using core::Vec3;
using core::VecRef;

PointMass::PointMass(std::string name, const PointMassParams& params)
    : Body(std::move(name)), params_(params) {
  if (!(params_.mass > 0.0)) throw std::invalid_argument("point mass: mass must be > 0");
}

std::vector<std::string> PointMass::state_labels() const {
  return {"p.x", "p.y", "p.z", "v.x", "v.y", "v.z"};
}

void PointMass::initial_state(VecRef x) const {
  x.segment<3>(0) = params_.position;
  x.segment<3>(3) = params_.velocity;
}

void PointMass::derivative(ConstVecRef x, ConstVecRef u_hat, VecRef x_dot) const {
  x_dot.segment<3>(0) = x.segment<3>(3);
  x_dot.segment<3>(3) = u_hat.segment<3>(0) / params_.mass + params_.gravity;
}

std::vector<core::SignalInfo> PointMass::signals() const {
  return {{.name = "p", .axes = core::xyz_axes(), .unit = "m", .frame = "world",
           .description = "position"},
          {.name = "v", .axes = core::xyz_axes(), .unit = "m/s", .frame = "world",
           .description = "velocity"}};
}

void PointMass::write_signals(ConstVecRef x, VecRef out) const { out.head<6>() = x.head<6>(); }

double PointMass::energy(ConstVecRef x) const {
  const Vec3 v = x.segment<3>(3);
  return 0.5 * params_.mass * v.squaredNorm() - params_.mass * params_.gravity.dot(x.segment<3>(0));
}

}  // namespace stiction::components
