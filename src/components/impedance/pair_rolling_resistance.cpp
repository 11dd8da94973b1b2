#include "components/impedance/pair_rolling_resistance.hpp"

#include <cmath>
#include <stdexcept>

#include "components/impedance/friction_law.hpp"

namespace stiction::components {

using core::ConstVecRef;
using core::Vec3;
using core::VecRef;

namespace {

Vec3 normal_of(ConstVecRef x_hat) { return x_hat.segment<3>(1); }
Vec3 relative_w(ConstVecRef x_hat) { return x_hat.segment<3>(7); }
Vec3 tangential(const Vec3& v, const Vec3& n) { return v - n.dot(v) * n; }

}  // namespace

PairRollingResistance::PairRollingResistance(std::string name, const PairContactParams& contact,
                                             const RollingResistanceParams& params)
    : Impedance(std::move(name)),
      FrictionSpring(params.stiffness, params.damping),
      contact_("contact", contact),
      params_(params) {
  check_rolling_params(params_);
}

std::vector<std::string> PairRollingResistance::state_labels() const {
  if (dimension() == 1) return {"e"};
  return {"e.x", "e.y", "e.z"};
}

void PairRollingResistance::evaluate(double /*t*/, ConstVecRef x_hat, ConstVecRef y, double tau,
                                     VecRef u, VecRef y_dot) const {
  const Vec3 n = normal_of(x_hat);
  const Vec3 w = relative_w(x_hat);
  const double K = params_.stiffness;
  const double BtK = params_.damping + tau * K;
  // (19b) on the relative angular slip, with the level c N (plain gsat, friction_law.hpp).
  const double level = params_.coefficient * contact_.contact_normal_force(x_hat.head<7>());
  const FrictionLevels levels{level, level, 0.0, 0.0};
  if (params_.part == RollingPart::spin) {
    const double s = n.dot(w);
    double f = BtK * s + K * y[0];
    if (std::abs(f) <= levels.breakaway) {
      y_dot[0] = s;  // exactly the relative spin while stuck: no creep
    } else {
      f = std::copysign(levels.sliding_force(std::abs(f), BtK), f);
      y_dot[0] = (f - K * y[0]) / BtK;
    }
    u.head<3>() = f * n;
    return;
  }
  const Vec3 w_t = tangential(w, n);
  const Vec3 e = y.head<3>();
  Vec3 f = BtK * w_t + K * tangential(e, n);
  const double norm = f.norm();
  if (norm <= levels.breakaway) {
    y_dot.head<3>() = w_t;  // exactly w_t while stuck: no creep
  } else {
    f *= norm > 0.0 ? levels.sliding_force(norm, BtK) / norm : 0.0;
    // The whole e: a normal part left behind by a turning normal relaxes (as PairContact).
    y_dot.head<3>() = (f - K * e) / BtK;
  }
  u.head<3>() = f;
}

int PairRollingResistance::regime(ConstVecRef x_hat, ConstVecRef y, double tau) const {
  if (contact_.contact_normal_force(x_hat.head<7>()) == 0.0) return 0;  // open
  Vec3 u;
  Vec3 y_dot = Vec3::Zero();
  evaluate(0.0, x_hat, y, tau, u, y_dot.head(dimension()));
  if (params_.part == RollingPart::spin)
    return y_dot[0] == normal_of(x_hat).dot(relative_w(x_hat)) ? 1 : 2;
  return y_dot == tangential(relative_w(x_hat), normal_of(x_hat)) ? 1 : 2;
}

Vec3 PairRollingResistance::slip_velocity(ConstVecRef x_hat) const {
  const Vec3 n = normal_of(x_hat);
  const Vec3 w = relative_w(x_hat);
  if (params_.part == RollingPart::spin) return n.dot(w) * n;
  return tangential(w, n);
}

Vec3 PairRollingResistance::unloaded_slip(ConstVecRef x_hat, ConstVecRef y, double tau) const {
  const Vec3 n = normal_of(x_hat);
  const double gain = -params_.stiffness / (params_.damping + tau * params_.stiffness);
  if (params_.part == RollingPart::spin) return gain * y[0] * n;
  return gain * tangential(y.head<3>(), n);
}

std::vector<core::SignalInfo> PairRollingResistance::signals() const {
  const bool spin = params_.part == RollingPart::spin;
  return {{.name = "tau",
           .axes = core::xyz_axes(),
           .unit = "N·m",
           .frame = "world",
           .description = spin ? "spinning resistance torque on the first body; the other "
                                 "body receives the opposite"
                               : "rolling resistance torque on the first body; the other body "
                                 "receives the opposite"},
          {.name = "e",
           .axes = spin ? std::vector<std::string>{} : core::xyz_axes(),
           .unit = "rad",
           .frame = spin ? "surface" : "world",
           .description = "elastic rotation of the resistance element (anchor offset)"}};
}

void PairRollingResistance::write_signals(ConstVecRef /*x_hat*/, ConstVecRef y, ConstVecRef u,
                                          VecRef out) const {
  out.segment<3>(0) = -u.head<3>();
  out.segment(3, dimension()) = y.head(dimension());
}

}  // namespace stiction::components
