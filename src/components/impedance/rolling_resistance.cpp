#include "components/impedance/rolling_resistance.hpp"

#include <cmath>
#include <stdexcept>

#include "components/impedance/friction_law.hpp"

namespace stiction::components {

using core::ConstVecRef;
using core::Vec3;
using core::VecRef;

RollingResistance::RollingResistance(std::string name, const KikuuweContactParams& contact,
                                     const RollingResistanceParams& params)
    : Impedance(std::move(name)),
      FrictionSpring(params.stiffness, params.damping),
      contact_("contact", contact),
      params_(params) {
  check_rolling_params(params_);
}

void check_rolling_params(const RollingResistanceParams& p) {
  if (!(p.coefficient >= 0.0) || !std::isfinite(p.coefficient) || !(p.stiffness > 0.0) ||
      !std::isfinite(p.stiffness) || !(p.damping >= 0.0) || !std::isfinite(p.damping) ||
      !(p.radius >= 0.0)) {
    throw std::invalid_argument(
        "rolling resistance: need a coefficient >= 0, K > 0, B >= 0 and a radius >= 0");
  }
}

std::vector<std::string> RollingResistance::state_labels() const {
  if (dimension() == 1) return {"e"};
  return {"e.0", "e.1"};
}

Vec3 RollingResistance::axis_in_plane(ConstVecRef x_hat) const {
  const Vec3 a = x_hat.segment<3>(kCylinderAxis);
  return a - contact_.normal().dot(a) * contact_.normal();
}

Eigen::Vector2d RollingResistance::coordinates(ConstVecRef x_hat) const {
  const Vec3 w = x_hat.segment<3>(6);
  if (params_.part == RollingPart::spin) return {contact_.normal().dot(w), 0.0};
  if (params_.body == RollingBody::cylinder) return {axis_in_plane(x_hat).dot(w), 0.0};
  return {contact_.tangent1().dot(w), contact_.tangent2().dot(w)};
}

Vec3 RollingResistance::world(ConstVecRef x_hat, ConstVecRef c) const {
  if (params_.part == RollingPart::spin) return c[0] * contact_.normal();
  if (params_.body == RollingBody::cylinder) return c[0] * axis_in_plane(x_hat);
  return c[0] * contact_.tangent1() + c[1] * contact_.tangent2();
}

double RollingResistance::contact_normal_force(ConstVecRef x_hat) const {
  if (params_.body == RollingBody::cylinder) {
    // The rim points as the contact elements NAME.0-5 receive them (CylinderTwistMap): the
    // load of the whole cylinder on the plane, whichever points touch.
    double n = 0.0;
    for (int i = 0; i < core::RimPoint::kPoints; ++i) {
      n += contact_.contact_normal_force(x_hat.segment<6>(kCylinderRim + 6 * i));
    }
    return n;
  }
  // The contact's input, as ContactPointMap gives it for this sphere: its lowest point.
  const Vec3 lever = -params_.radius * contact_.normal();
  Eigen::Matrix<double, 6, 1> at;
  at.head<3>() = Vec3(x_hat.segment<3>(0)) + lever;
  at.tail<3>() = Vec3(x_hat.segment<3>(3)) + Vec3(x_hat.segment<3>(6)).cross(lever);
  return contact_.contact_normal_force(at);
}

void RollingResistance::evaluate(double /*t*/, ConstVecRef x_hat, ConstVecRef y, double tau,
                                 VecRef u, VecRef y_dot) const {
  const int n = dimension();
  const double K = params_.stiffness;
  const double BtK = params_.damping + tau * K;
  const Eigen::Vector2d w = coordinates(x_hat);
  // (19b) on the angular slip, with the level c N (plain gsat, friction_law.hpp).
  const double level = params_.coefficient * contact_normal_force(x_hat);
  const FrictionLevels levels{level, level, 0.0, 0.0};
  Eigen::Vector2d f = Eigen::Vector2d::Zero();
  f.head(n) = BtK * w.head(n) + K * y.head(n);
  const double norm = f.norm();
  if (norm <= levels.breakaway) {
    y_dot.head(n) = w.head(n);  // exactly w while stuck: no creep
  } else {
    f *= norm > 0.0 ? levels.sliding_force(norm, BtK) / norm : 0.0;
    y_dot.head(n) = (f.head(n) - K * y.head(n)) / BtK;
  }
  u.head<3>() = world(x_hat, f);
}

int RollingResistance::regime(ConstVecRef x_hat, ConstVecRef y, double tau) const {
  if (contact_normal_force(x_hat) == 0.0) return 0;  // open (see KikuuweContact::regime)
  Vec3 u;
  Eigen::Vector2d y_dot = Eigen::Vector2d::Zero();
  evaluate(0.0, x_hat, y, tau, u, y_dot.head(dimension()));
  const Eigen::Vector2d w = coordinates(x_hat);
  return y_dot.head(dimension()) == w.head(dimension()) ? 1 : 2;
}

Vec3 RollingResistance::slip_velocity(ConstVecRef x_hat) const {
  return world(x_hat, coordinates(x_hat));
}

Vec3 RollingResistance::unloaded_slip(ConstVecRef x_hat, ConstVecRef y, double tau) const {
  Eigen::Vector2d e = Eigen::Vector2d::Zero();
  e.head(dimension()) = y.head(dimension());
  return -params_.stiffness / (params_.damping + tau * params_.stiffness) * world(x_hat, e);
}

std::vector<core::SignalInfo> RollingResistance::signals() const {
  const bool spin = params_.part == RollingPart::spin;
  // A cylinder's rolling state is one angle about its axis (projected on the plane).
  const bool about_axis = !spin && params_.body == RollingBody::cylinder;
  return {
      {.name = "tau",
       .axes = core::xyz_axes(),
       .unit = "N·m",
       .frame = "world",
       .description = spin ? "spinning resistance torque on the body"
                           : "rolling resistance torque on the body"},
      {.name = "e",
       .axes = dimension() == 1 ? std::vector<std::string>{} : core::index_axes(2),
       .unit = "rad",
       .frame = about_axis ? "body" : "surface",
       .description = about_axis ? "elastic rotation of the resistance element about the axis "
                                   "projected on the plane (anchor offset)"
                                 : "elastic rotation of the resistance element (anchor offset)"}};
}

void RollingResistance::write_signals(ConstVecRef /*x_hat*/, ConstVecRef y, ConstVecRef u,
                                      VecRef out) const {
  out.segment<3>(0) = -u.head<3>();
  out.segment(3, dimension()) = y.head(dimension());
}

}  // namespace stiction::components
