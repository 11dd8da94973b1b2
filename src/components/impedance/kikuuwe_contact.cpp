#include "components/impedance/kikuuwe_contact.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/safe_normalize.hpp"

namespace stiction::components {

using core::ConstVecRef;
using core::Vec3;
using core::VecRef;

KikuuweContact::KikuuweContact(std::string name, const KikuuweContactParams& params)
    : Impedance(std::move(name)),
      ContactCapabilities(
          params.stiffness, params.damping, std::max({params.mu, params.mu_static, params.mu_2}),
          params.tangential_stiffness >= 0.0 ? params.tangential_stiffness : params.stiffness,
          static_to_kinetic(params.mu, params.mu_static)),
      params_(params) {
  const auto normal = core::safe_normalized(params_.normal);
  if (!normal) throw std::invalid_argument("contact: the normal must be a finite, non-zero vector");
  if (!(params_.stiffness > 0.0) || !(params_.damping >= 0.0) || !(params_.mu >= 0.0)) {
    throw std::invalid_argument("contact: need K > 0, B >= 0, mu >= 0");
  }
  n_ = *normal;
  // Tangent basis: world x projected on the plane (world y if the normal is close to x).
  const Vec3 seed = std::abs(n_.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  t1_ = (seed - seed.dot(n_) * n_).normalized();
  t2_ = n_.cross(t1_);
  kt_ = params_.tangential_stiffness > 0.0 ? params_.tangential_stiffness : params_.stiffness;
  bt_ = params_.tangential_damping >= 0.0 ? params_.tangential_damping : params_.damping;
  frame_ = {n_, t1_, t2_};
  coefficients_ = {
      params_.stiffness, params_.damping, kt_, bt_,
      contact_friction(params_.mu, params_.mu_static, params_.stribeck_velocity, params_.viscous)};
  // Anisotropic: mu's direction along t1, t2 (t1 itself by default).
  const Vec3 axis = params_.friction_axis;
  const Eigen::Vector2d in_plane = axis == Vec3::Zero()
                                       ? Eigen::Vector2d(1.0, 0.0)
                                       : Eigen::Vector2d(t1_.dot(axis), t2_.dot(axis));
  if (params_.mu_2 >= 0.0 && !(in_plane.norm() > 1e-9 * axis.norm())) {
    throw std::invalid_argument("contact: the friction axis must not be along the normal");
  }
  coefficients_.friction =
      contact_anisotropic_friction(coefficients_.friction, params_.mu_2, in_plane);
  bounded_ = params_.extent.bounded();
}

void KikuuweContact::evaluate_body_axes(ConstVecRef x_hat, ConstVecRef y, double tau, VecRef u,
                                        VecRef y_dot) const {
  // mu's direction from x_hat, along t1, t2 (unit); the direction at t = 0 when the axis has
  // turned along the normal.
  const Vec3 a = x_hat.segment<3>(6);
  Eigen::Vector2d axis(t1_.dot(a), t2_.dot(a));
  const double norm = axis.norm();
  axis = norm > 1e-9 * a.norm() ? Eigen::Vector2d(axis / norm) : coefficients_.friction.axis;
  const Vec3 v_c = x_hat.segment<3>(3);
  const Vec3 on_body = contact_law_along(frame_, coefficients_, normal_force(x_hat), v_c,
                                         y.head<2>(), tau, axis, y_dot.head<2>());
  u.head<3>() = -on_body;
}

int KikuuweContact::regime(ConstVecRef x_hat, ConstVecRef y, double tau) const {
  // Open when the normal force is zero. Not "when u is zero": a friction state decayed to
  // ~1e-170 during a flight makes |f| underflow to 0 <= mu N = 0, which reads as stuck.
  if (normal_force(x_hat) == 0.0) return 0;
  Eigen::Vector3d u;
  Eigen::Vector2d y_dot;
  evaluate(0.0, x_hat, y, tau, u, y_dot);
  const Eigen::Vector2d v_t(t1_.dot(Vec3(x_hat.segment<3>(3))), t2_.dot(Vec3(x_hat.segment<3>(3))));
  return y_dot == v_t ? 1 : 2;  // stuck (eps == v exactly) or sliding
}

void KikuuweContact::evaluate_friction_held(double /*t*/, ConstVecRef x_hat, ConstVecRef /*y*/,
                                            double /*tau*/, ConstVecRef u_ref,
                                            ConstVecRef y_dot_ref, VecRef u, VecRef y_dot) const {
  const Vec3 held = u_ref.head<3>();
  u.head<3>() = held - n_.dot(held) * n_ - normal_force(x_hat) * n_;
  y_dot.head<2>() = y_dot_ref.head<2>();
}

Vec3 KikuuweContact::slip_velocity(ConstVecRef x_hat) const {
  const Vec3 v_c = x_hat.segment<3>(3);
  return v_c - n_.dot(v_c) * n_;
}

Vec3 KikuuweContact::unloaded_slip(ConstVecRef /*x_hat*/, ConstVecRef y, double tau) const {
  return -kt_ / (bt_ + tau * kt_) * (y[0] * t1_ + y[1] * t2_);
}

double KikuuweContact::stored_energy(ConstVecRef x_hat, ConstVecRef y) const {
  const Vec3 p_c = x_hat.segment<3>(0);
  const bool inside = !bounded_ || params_.extent.contains(p_c - params_.extent.centre);
  const double depth = inside ? std::max(0.0, params_.offset - n_.dot(p_c)) : 0.0;
  return 0.5 * params_.stiffness * depth * depth + 0.5 * kt_ * y.head<2>().squaredNorm();
}

std::vector<core::SignalInfo> KikuuweContact::signals() const {
  return {{.name = "f",
           .axes = core::xyz_axes(),
           .unit = "N",
           .frame = "world",
           .description = "contact force on the body (normal plus friction)"},
          {.name = "slip",
           .axes = core::xyz_axes(),
           .unit = "m/s",
           .frame = "world",
           .description = "velocity of the contact point in the surface plane"},
          {.name = "e",
           .axes = core::index_axes(2),
           .unit = "m",
           .frame = "surface",
           .description = "elastic displacement of the tangential friction element"},
          {.name = "n_force", .unit = "N", .description = "normal force magnitude"}};
}

void KikuuweContact::write_signals(ConstVecRef x_hat, ConstVecRef y, ConstVecRef u,
                                   VecRef out) const {
  const Vec3 v_c = x_hat.segment<3>(3);
  const Vec3 on_body = -u.head<3>();
  out.segment<3>(0) = on_body;
  out.segment<3>(3) = v_c - n_.dot(v_c) * n_;
  out.segment<2>(6) = y.head<2>();
  out[8] = n_.dot(on_body);
}

}  // namespace stiction::components
