// The friction law of every Kikuuwe element (kikuuwe_friction, the contacts): static and
// kinetic levels, a Stribeck curve and viscous friction, in the rate-dependent implicit form
// of Kikuuwe et al. 2006 (IEEE T-RO 22(6), "Admittance and impedance representations of
// friction based on implicit Euler integration"), written once here.
//
// The element (paper eq. 19) is a spring K and damper B in series with an anchor that slides
// on the ground. Over the stage step tau its implicit update gives the trial force
//   z = (B + tau K) v + K e,
// the force it would carry if the anchor did not move. The anchor's velocity w is then
// z's direction times a slip speed s >= 0, and the force is f = z - (B + tau K) w. The law
// the anchor obeys is
//   f in F(s) Sgn(w) + B_v w,   F(s) = F_k + (F_s - F_k) exp(-(s / v_s)^2)   (Stribeck)
// evaluated at the anchor's velocity that this very step gives (implicit, not lagged):
// - stuck (s = 0) while |z| <= F_s: f = z and e_dot = v exactly (the caller writes it as
//   such, so that a stuck element does not drift by a single bit, DESIGN section 1);
// - sliding otherwise: s solves  F(s) + (B + tau K + B_v) s = |z|, the force is
//   f = (F(s) + B_v s) z / |z|, and e_dot = (f - K e) / (B + tau K) as in (19).
// A steady slide (e constant) has w = v, so the force is F(|v|) + B_v |v|: F_k + B_v |v|
// once |v| >> v_s. Breakaway happens when |z| first exceeds F_s.
//
// v_s = 0 means no Stribeck curve: the level drops from F_s to F_k as soon as the anchor
// moves (the classical static/kinetic pair). With F_s = F_k and B_v = 0 the law is the plain
// gsat of eq. (15): `sliding_force` returns F_k itself, so the plain element computes exactly
// what it did before the law had levels (bit for bit).
//
// When the weakening is steeper than the damping, max |F'(s)| = (F_s - F_k) sqrt(2/e) / v_s
// > B + tau K + B_v, the equation for s can have three roots; the law takes the smallest, the
// one reached continuously from sticking as |z| grows (the 2006 paper asks for a step small
// enough to make the root unique; a contact's F_s = mu_s N grows with N, so no step can
// promise that here).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace stiction::components {

struct FrictionLevels {
  double kinetic = 0.0;            // F_k (N or N m)
  double breakaway = 0.0;          // F_s >= F_k, the edge of the stuck band
  double stribeck_velocity = 0.0;  // v_s (m/s or rad/s); 0: none
  double viscous = 0.0;            // B_v (N s/m or N m s/rad), outside the stuck band only

  // Plain Coulomb: one level, no viscous part (v_s is then irrelevant).
  bool plain() const { return breakaway == kinetic && viscous == 0.0; }

  // The Stribeck level F(s) at the anchor's slip speed s >= 0.
  double level(double s) const {
    if (!(stribeck_velocity > 0.0)) return s > 0.0 ? kinetic : breakaway;
    const double r = s / stribeck_velocity;
    return kinetic + (breakaway - kinetic) * std::exp(-r * r);
  }

  // The anchor's slip speed for a trial force of magnitude `trial` > breakaway, with
  // `damping_sum` = B + tau K (> 0).
  double slip_speed(double trial, double damping_sum) const {
    const double c = damping_sum + viscous;
    const double weakening = breakaway - kinetic;
    // Without a curve F(s) = F_k for s > 0: linear.
    if (!(stribeck_velocity > 0.0) || !(weakening > 0.0)) return (trial - kinetic) / c;
    const double vs = stribeck_velocity;
    const auto g = [&](double s) { return level(s) + c * s; };
    const auto dg = [&](double s) {
      const double r = s / vs;
      return c - weakening * 2.0 * r / vs * std::exp(-r * r);
    };
    // Every root lies in [(trial - F_s) / c, (trial - F_k) / c] since F_k <= F <= F_s.
    double lo = std::max(0.0, (trial - breakaway) / c);
    double hi = (trial - kinetic) / c;
    // g is concave up to s* = v_s / sqrt(2) (where g' is least) and convex beyond: if g' < 0
    // there, g rises to a maximum at s_a < s*, falls to a minimum at s_b > s*, then rises.
    const double s_star = vs / std::sqrt(2.0);
    if (dg(s_star) < 0.0) {
      const auto zero_of_dg = [&](double a, double b) {  // g' changes sign once on [a, b]
        const bool rising = dg(a) < 0.0;
        for (int k = 0; k < 200 && b - a > 1e-15 * b; ++k) {
          const double m = 0.5 * (a + b);
          ((dg(m) < 0.0) == rising ? a : b) = m;
        }
        return 0.5 * (a + b);
      };
      const double s_a = zero_of_dg(0.0, s_star);
      if (g(s_a) >= trial) {
        hi = std::min(hi, s_a);  // the smallest root is on the first rising branch
      } else {
        lo = std::max(lo, zero_of_dg(s_star, std::max(hi, s_star)));  // past the minimum
      }
    }
    // g is increasing on [lo, hi] with g(lo) <= trial <= g(hi): Newton kept in the bracket,
    // bisecting where it would leave it.
    double s = hi;
    for (int k = 0; k < 100; ++k) {
      const double r = g(s) - trial;
      if (r == 0.0) return s;
      (r > 0.0 ? hi : lo) = s;
      double next = s - r / dg(s);
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      if (std::abs(next - s) <= 4e-16 * s || hi - lo <= 4e-16 * hi) return next;
      s = next;
    }
    return s;
  }

  // |f| while sliding, for a trial force of magnitude `trial` > breakaway and
  // `damping_sum` = B + tau K.
  double sliding_force(double trial, double damping_sum) const {
    if (plain()) return kinetic;                         // eq. (15): exactly the Coulomb level
    if (!(damping_sum + viscous > 0.0)) return kinetic;  // no damping at all: Coulomb
    const double s = slip_speed(trial, damping_sum);
    return level(s) + viscous * s;
  }
};

// The point of the ellipse {x : (x_1 / a_1)^2 + (x_2 / a_2)^2 <= 1} (semi-axes a_i > 0)
// nearest to z in the Euclidean norm, for z outside it (issue 38 item 2). It is
// x_i = a_i^2 z_i / (a_i^2 + t) with t > 0 the root of
//   S(t) = sum_i (a_i z_i / (a_i^2 + t))^2 = 1,
// found by Newton's method on phi(t) = S(t)^(-1/2) - 1 (increasing, and linear when a_1 =
// a_2) inside the bracket [|c| - max a_i^2, |c| - min a_i^2], c_i = a_i z_i, where S's bounds
// |c|^2 / (a_max^2 + t)^2 <= S(t) <= |c|^2 / (a_min^2 + t)^2 put the root; bisection where a
// Newton step would leave the bracket.
inline Eigen::Vector2d nearest_on_ellipse(const Eigen::Vector2d& z, double a1, double a2) {
  const double b1 = a1 * a1, b2 = a2 * a2;
  const double c1 = a1 * z.x(), c2 = a2 * z.y();
  const double c = std::hypot(c1, c2);
  if (!(c > 0.0)) return Eigen::Vector2d::Zero();  // semi-axes or z underflowed: no force
  double lo = std::max(0.0, c - std::max(b1, b2)), hi = c - std::min(b1, b2);
  double t = lo;
  for (int k = 0; k < 100 && hi > lo; ++k) {
    const double r1 = c1 / (b1 + t), r2 = c2 / (b2 + t);
    const double S = r1 * r1 + r2 * r2;
    const double phi = 1.0 / std::sqrt(S) - 1.0;
    if (phi == 0.0) break;
    (phi < 0.0 ? lo : hi) = t;
    const double dphi = (r1 * r1 / (b1 + t) + r2 * r2 / (b2 + t)) / (S * std::sqrt(S));
    double next = t - phi / dphi;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - t) <= 4e-16 * t) {
      t = next;
      break;
    }
    t = next;
  }
  return {b1 * z.x() / (b1 + t), b2 * z.y() / (b2 + t)};
}

// Friction coefficients of a contact: the levels are the coefficients times the normal force
// N, the viscous coefficient acts only while the contact carries a load (N > 0).
// Anisotropic friction (mu_2 >= 0, issue 38 item 2): the coefficient is mu along the unit
// direction `axis` of the surface (coordinates along the contact's tangents t1, t2) and mu_2
// across it, with the elliptic limit {f : (f_a / mu)^2 + (f_b / mu_2)^2 <= N^2}; only the
// plain kinetic level goes with it (contact_anisotropic_friction checks).
struct ContactFriction {
  double mu = 0.1;                 // kinetic
  double mu_static = 0.1;          // >= mu
  double stribeck_velocity = 0.0;  // m/s, 0: none
  double viscous = 0.0;            // N s/m
  double mu_2 = -1.0;              // across `axis`; < 0: isotropic (mu everywhere)
  Eigen::Vector2d axis{1.0, 0.0};  // the direction of mu, along t1, t2 (unit)

  bool anisotropic() const { return mu_2 >= 0.0; }

  FrictionLevels at(double normal_force) const {
    return {mu * normal_force, mu_static * normal_force, stribeck_velocity,
            normal_force > 0.0 ? viscous : 0.0};
  }
};

// mu_static / mu as a contact's parameters give them (mu_static < 0: equal to mu); 1 when
// mu = 0 (no friction: nothing breaks away).
inline double static_to_kinetic(double mu, double mu_static) {
  return mu > 0.0 && mu_static > mu ? mu_static / mu : 1.0;
}

// The coefficients as a contact's parameters give them (mu_static < 0: equal to mu), checked:
// std::invalid_argument unless 0 <= mu <= mu_static, v_s >= 0 and B_v >= 0, all finite.
inline ContactFriction contact_friction(double mu, double mu_static, double stribeck_velocity,
                                        double viscous) {
  const ContactFriction c{mu, mu_static < 0.0 ? mu : mu_static, stribeck_velocity, viscous};
  if (!(c.mu >= 0.0 && c.mu_static >= c.mu && std::isfinite(c.mu_static) &&
        c.stribeck_velocity >= 0.0 && std::isfinite(c.stribeck_velocity) && c.viscous >= 0.0 &&
        std::isfinite(c.viscous))) {
    throw std::invalid_argument(
        "contact: need 0 <= mu <= mu_static, stribeck_velocity >= 0 and viscous >= 0, finite");
  }
  return c;
}

// An anisotropic contact's coefficients: mu along `axis` (a direction in the t1, t2
// coordinates of the surface, normalized here) and mu_2 across it, both > 0 and finite, with
// the plain kinetic law only (a static level, a Stribeck curve or viscous friction over an
// ellipse is not defined here). mu_2 == mu gives the isotropic law itself (bit for bit).
// std::invalid_argument otherwise.
inline ContactFriction contact_anisotropic_friction(const ContactFriction& isotropic, double mu_2,
                                                    const Eigen::Vector2d& axis) {
  ContactFriction c = isotropic;
  if (mu_2 < 0.0 || mu_2 == c.mu) return c;
  if (!(c.mu > 0.0 && mu_2 > 0.0 && std::isfinite(c.mu) && std::isfinite(mu_2))) {
    throw std::invalid_argument(
        "contact: anisotropic friction needs mu_1 > 0 and mu_2 > 0, finite");
  }
  if (!(c.mu_static == c.mu && c.stribeck_velocity == 0.0 && c.viscous == 0.0)) {
    throw std::invalid_argument(
        "contact: anisotropic friction takes the kinetic level only (no mu_static, "
        "stribeck_velocity or viscous)");
  }
  const double norm = axis.norm();
  if (!(norm > 0.0) || !std::isfinite(norm)) {
    throw std::invalid_argument("contact: the friction axis must lie in the surface");
  }
  c.mu_2 = mu_2;
  c.axis = axis / norm;
  return c;
}

}  // namespace stiction::components
