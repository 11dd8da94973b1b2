#include "components/impedance/pair_contact.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace stiction::components {

using core::ConstVecRef;
using core::Vec3;
using core::VecRef;

namespace {

Vec3 normal_of(ConstVecRef x_hat) { return x_hat.segment<3>(1); }
Vec3 tangential(const Vec3& v, const Vec3& n) { return v - n.dot(v) * n; }

}  // namespace

PairContact::PairContact(std::string name, const PairContactParams& params)
    : Impedance(std::move(name)),
      ContactCapabilities(
          params.stiffness, params.damping, std::max(params.mu, params.mu_static),
          params.tangential_stiffness > 0.0 ? params.tangential_stiffness : params.stiffness,
          static_to_kinetic(params.mu, params.mu_static)),
      params_(params) {
  if (!(params_.stiffness > 0.0) || !(params_.damping >= 0.0) || !(params_.mu >= 0.0)) {
    throw std::invalid_argument("contact: need K > 0, B >= 0, mu >= 0");
  }
  const double kt =
      params_.tangential_stiffness > 0.0 ? params_.tangential_stiffness : params_.stiffness;
  const double bt =
      params_.tangential_damping >= 0.0 ? params_.tangential_damping : params_.damping;
  coefficients_ = {
      params_.stiffness, params_.damping, kt, bt,
      contact_friction(params_.mu, params_.mu_static, params_.stribeck_velocity, params_.viscous)};
}

double PairContact::contact_normal_force(ConstVecRef x_hat) const {
  const Vec3 v_rel = x_hat.segment<3>(4);
  return components::contact_normal_force(coefficients_, x_hat[0], normal_of(x_hat).dot(v_rel));
}

double PairContact::contact_closure(ConstVecRef x_hat) const {
  const Vec3 v_rel = x_hat.segment<3>(4);
  return components::contact_closure(coefficients_, x_hat[0], normal_of(x_hat).dot(v_rel));
}

void PairContact::evaluate(double /*t*/, ConstVecRef x_hat, ConstVecRef y, double tau, VecRef u,
                           VecRef y_dot) const {
  const Vec3 n = normal_of(x_hat);
  const Vec3 v_t = tangential(x_hat.segment<3>(4), n);
  const Vec3 e = y.head<3>();
  const double BtK = coefficients_.bt + tau * coefficients_.kt;
  Vec3 f = BtK * v_t + coefficients_.kt * tangential(e, n);
  const FrictionLevels levels = coefficients_.friction.at(contact_normal_force(x_hat));
  const double norm = f.norm();
  if (norm <= levels.breakaway) {
    y_dot.head<3>() = v_t;  // exactly v_t while stuck, as for a plane (contact_law.hpp)
  } else {
    f *= norm > 0.0 ? levels.sliding_force(norm, BtK) / norm : 0.0;
    y_dot.head<3>() = (f - coefficients_.kt * e) / BtK;
  }
  // u is the negative of the force on the first body: N n - f.
  u.head<3>() = f - contact_normal_force(x_hat) * n;
}

int PairContact::regime(ConstVecRef x_hat, ConstVecRef y, double tau) const {
  if (contact_normal_force(x_hat) == 0.0) return 0;  // open (see KikuuweContact::regime)
  Vec3 u, y_dot;
  evaluate(0.0, x_hat, y, tau, u, y_dot);
  return y_dot == slip_velocity(x_hat) ? 1 : 2;
}

void PairContact::evaluate_friction_held(double /*t*/, ConstVecRef x_hat, ConstVecRef /*y*/,
                                         double /*tau*/, ConstVecRef u_ref, ConstVecRef y_dot_ref,
                                         VecRef u, VecRef y_dot) const {
  const Vec3 n = normal_of(x_hat);
  u.head<3>() = tangential(u_ref.head<3>(), n) - contact_normal_force(x_hat) * n;
  y_dot.head<3>() = y_dot_ref.head<3>();
}

Vec3 PairContact::slip_velocity(ConstVecRef x_hat) const {
  return tangential(x_hat.segment<3>(4), normal_of(x_hat));
}

double PairContact::gap(ConstVecRef x_hat) const {
  return params_.gap_is_distance ? -x_hat[0] : std::numeric_limits<double>::quiet_NaN();
}

double PairContact::approach_speed(ConstVecRef x_hat) const {
  // The contact point's relative velocity bounds the rate the distance closes at.
  return x_hat.segment<3>(4).norm();
}

Vec3 PairContact::unloaded_slip(ConstVecRef x_hat, ConstVecRef y, double tau) const {
  const double kt = coefficients_.kt;
  return -kt / (coefficients_.bt + tau * kt) * tangential(y.head<3>(), normal_of(x_hat));
}

double PairContact::stored_energy(ConstVecRef x_hat, ConstVecRef y) const {
  const double d = std::max(0.0, x_hat[0]);
  const Vec3 e_t = tangential(y.head<3>(), normal_of(x_hat));
  return 0.5 * coefficients_.k * d * d + 0.5 * coefficients_.kt * e_t.squaredNorm();
}

std::vector<core::SignalInfo> PairContact::signals() const {
  return {{.name = "f",
           .axes = core::xyz_axes(),
           .unit = "N",
           .frame = "world",
           .description = "contact force on the first body (normal plus friction); the other "
                          "body receives the opposite"},
          {.name = "slip",
           .axes = core::xyz_axes(),
           .unit = "m/s",
           .frame = "world",
           .description = "velocity of the first body's contact point relative to the other's, "
                          "in the tangent plane"},
          {.name = "e",
           .axes = core::xyz_axes(),
           .unit = "m",
           .frame = "world",
           .description = "elastic displacement of the tangential friction element"},
          {.name = "n_force", .unit = "N", .description = "normal force magnitude"}};
}

void PairContact::write_signals(ConstVecRef x_hat, ConstVecRef y, ConstVecRef u, VecRef out) const {
  const Vec3 on_body = -u.head<3>();
  out.segment<3>(0) = on_body;
  out.segment<3>(3) = slip_velocity(x_hat);
  out.segment<3>(6) = y.head<3>();
  out[9] = normal_of(x_hat).dot(on_body);
}

}  // namespace stiction::components
