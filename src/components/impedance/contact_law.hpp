// Kikuuwe's contact law (paper eqs. 23-24) for one contact point, shared by the fixed and
// the moving surfaces. Given the penetration `depth` (> 0 in contact) and the contact
// point's velocity relative to the surface `v_rel` (world), it returns the force on the
// body and the rate of the 2-D friction state e (coordinates along t1, t2):
//   N = max(0, K d - B n.v_rel)   (0 when d <= 0: no adhesion, mu N never negative)
//   f = gsat(mu N, (Bt + tau Kt) v_t + Kt e),  e_dot = v_t while unsaturated (exactly),
//   else (f - Kt e) / (Bt + tau Kt);  force on the body = N n - (f1 t1 + f2 t2),
// where gsat is friction_law.hpp's: stuck up to mu_static N, then sliding at the Stribeck
// level between mu_static N and mu N plus viscous friction (the plain gsat with mu alone).
// With N = 0 the force is zero and e relaxes through e_dot = -Kt e / (Bt + tau Kt).
#pragma once

#include <algorithm>
#include <utility>

#include "components/impedance/friction_law.hpp"
#include "core/types.hpp"

namespace stiction::components {

struct ContactFrame {
  core::Vec3 n, t1, t2;
};

struct ContactCoefficients {
  double k, b, kt, bt;
  ContactFriction friction;
};

inline double contact_normal_force(const ContactCoefficients& c, double depth, double v_n) {
  return depth > 0.0 ? std::max(0.0, c.k * depth - c.b * v_n) : 0.0;
}

// core::NormalContact::contact_closure of that law: min(K d, K d - B v_n), continuous, > 0
// exactly where N > 0 (pressed and not pulling away faster than the spring pushes). A
// touch-down crosses zero with the depth (K d), a lift-off with the law's force.
inline double contact_closure(const ContactCoefficients& c, double depth, double v_n) {
  return std::min(c.k * depth, c.k * depth - c.b * v_n);
}

// The elliptic limit of anisotropic friction (friction_law.hpp's ContactFriction): the
// implicit update of eq. (19) with the anchor's velocity w in the normal cone of the
// ellipse E = {f : (f_a / (mu N))^2 + (f_b / (mu_2 N))^2 <= 1} (maximum dissipation):
//   f = z - (Bt + tau Kt) w,  f in E,  w normal to E at f,
// whose solution is the Euclidean projection of the trial force z onto E: f = z while z is
// inside (stuck, e_dot = v_t exactly), the nearest point of E's boundary otherwise. A steady
// slide (w = v) then carries the maximum-dissipation force
//   f = N M^2 v / |M v|,  M = diag(mu, mu_2) along (axis, its normal in the surface).
// (Projecting radially, in coordinates scaled so that E is a circle, would give f parallel
// to v instead: the same limit, the wrong direction.) `axis` is mu's direction along t1, t2.
template <typename Rate>
inline void elliptic_friction(const ContactFriction& friction, const Eigen::Vector2d& axis,
                              double normal_force, const Eigen::Vector2d& v_t, double kt,
                              double BtK, const Eigen::Vector2d& e, Eigen::Vector2d& f,
                              Rate&& e_dot) {
  const double a1 = friction.mu * normal_force, a2 = friction.mu_2 * normal_force;
  const Eigen::Vector2d across(-axis.y(), axis.x());
  const double z1 = axis.dot(f), z2 = across.dot(f);
  const double p1 = z1 * a2, p2 = z2 * a1;
  // Stuck inside the ellipse; with no load (a1 = a2 = 0) only when z = 0, as the isotropic law.
  const bool inside =
      a1 > 0.0 ? p1 * p1 + p2 * p2 <= (a1 * a2) * (a1 * a2) : z1 == 0.0 && z2 == 0.0;
  if (inside) {
    e_dot = v_t;  // exactly v while stuck, as in the isotropic law
    return;
  }
  if (!(a1 > 0.0)) {
    f.setZero();  // no load: no friction, e relaxes
  } else {
    const Eigen::Vector2d g = nearest_on_ellipse(Eigen::Vector2d(z1, z2), a1, a2);
    f = g.x() * axis + g.y() * across;
  }
  e_dot = (f - kt * e) / BtK;
}

// Returns the force on the body; writes e's rate to e_dot. `axis` is the direction of mu
// for an anisotropic law (along t1, t2; unused when isotropic).
template <typename Rate>
inline core::Vec3 contact_law_along(const ContactFrame& fr, const ContactCoefficients& c,
                                    double normal_force, const core::Vec3& v_rel,
                                    const Eigen::Vector2d& e, double tau,
                                    const Eigen::Vector2d& axis, Rate&& e_dot) {
  const Eigen::Vector2d v_t(fr.t1.dot(v_rel), fr.t2.dot(v_rel));
  const double BtK = c.bt + tau * c.kt;
  Eigen::Vector2d f = BtK * v_t + c.kt * e;
  if (c.friction.anisotropic()) {
    elliptic_friction(c.friction, axis, normal_force, v_t, c.kt, BtK, e, f, e_dot);
    return normal_force * fr.n - (f.x() * fr.t1 + f.y() * fr.t2);
  }
  const FrictionLevels levels = c.friction.at(normal_force);
  const double norm = f.norm();
  if (norm <= levels.breakaway) {
    e_dot = v_t;  // exactly v while stuck (see kikuuwe_friction.cpp)
  } else {
    f *= norm > 0.0 ? levels.sliding_force(norm, BtK) / norm : 0.0;
    e_dot = (f - c.kt * e) / BtK;
  }
  return normal_force * fr.n - (f.x() * fr.t1 + f.y() * fr.t2);
}

// The same with the surface-fixed axis of an anisotropic law (c.friction.axis).
template <typename Rate>
inline core::Vec3 contact_law(const ContactFrame& fr, const ContactCoefficients& c,
                              double normal_force, const core::Vec3& v_rel,
                              const Eigen::Vector2d& e, double tau, Rate&& e_dot) {
  return contact_law_along(fr, c, normal_force, v_rel, e, tau, c.friction.axis,
                           std::forward<Rate>(e_dot));
}

}  // namespace stiction::components
