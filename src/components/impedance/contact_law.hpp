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

// Returns the force on the body; writes e's rate to e_dot and the friction force to f_out.
template <typename Rate>
inline core::Vec3 contact_law(const ContactFrame& fr, const ContactCoefficients& c,
                              double normal_force, const core::Vec3& v_rel,
                              const Eigen::Vector2d& e, double tau, Rate&& e_dot) {
  const Eigen::Vector2d v_t(fr.t1.dot(v_rel), fr.t2.dot(v_rel));
  const double BtK = c.bt + tau * c.kt;
  Eigen::Vector2d f = BtK * v_t + c.kt * e;
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

}  // namespace stiction::components
