// Rolling and spinning resistance of a sphere or a cylinder on a fixed plane (issue 38 item
// 3): a Kikuuwe element (eq. 19, friction_law.hpp's plain gsat) on the body's angular
// velocity relative to the plane, with the level c N, c a length (the lever arm of the
// normal force N):
// - part `rolling`, a sphere: the tangential part w_t = w - (n.w) n, a 2-D state e along the
//   plane's tangents t1, t2 (rad), level `rolling_resistance` * N (a ball rolls about any
//   axis in the plane);
// - part `rolling`, a cylinder: the 1-D coordinate a_p.w, a_p = a - (n.a) n the body's axis a
//   projected on the plane (not normalized), state e (rad), level `rolling_resistance` * N,
//   torque -f a_p on the body. A cylinder rolls about its axis only: on its rim (|a_p| = 1)
//   this is a torque up to c N about the axis; flat on a face (a_p = 0) nothing, since a face
//   does not roll; leaning on an edge, up to c N |a_p|. Why not the whole w_t as for a ball:
//   on its rim the other tangential direction is a tip onto one rim, which the rim contacts
//   carry, and flat on a face w_t is a wobble, not a roll. Why a_p unnormalized: the
//   coordinate (a Jacobian row a_p^T, the paper's Psi) and its torque (Phi, a_p f) stay
//   continuous when the cylinder lies down, where the direction of a_p is undefined;
// - part `spin`: the normal part n.w, a 1-D state e (rad), level `spin_friction` * N (a coin
//   spun on its face, a cylinder turned about the normal on its rim).
// While stuck, e_dot equals the coordinate exactly (as for every Kikuuwe element), so a body
// that has stopped rolling or spinning stays put without creep.
// N is the load the body's contact elements carry (kikuuwe_contact.hpp, computed by a copy of
// that contact from the same parameters, bit for bit): a sphere's one point; a cylinder's
// six rim points summed (those not touching give 0). No load, no resistance (regime 0).
// Not a core::NormalContact on purpose: the run's events would then take it for one more
// contact point of the sphere and report body states (stick, partial slip) over it; its own
// stick/slip events are a joint friction's.
// Input, a sphere: x_hat = [p (3), v (3), w (3)], the sphere centre's world position and
// velocity and its world angular velocity (BodyTwistMap); a cylinder: those, its axis in
// world coordinates and its rim points' [p_c, v_c] (CylinderTwistMap, kCylinderInput
// entries). Output u = the torque the body exerts on the element (world): the body receives
// -u, a free torque.
// Signals: tau (x y z, the torque on the body, world) and e (a sphere's rolling: axes 0 1
// along t1, t2; a cylinder's rolling and every spin: one entry).
#pragma once

#include "components/impedance/friction_capabilities.hpp"
#include "components/impedance/kikuuwe_contact.hpp"
#include "core/impedance.hpp"
#include "core/rim_point.hpp"

namespace stiction::components {

enum class RollingPart { rolling, spin };
// The body whose contact the element rides on: what it rolls about and where N comes from.
enum class RollingBody { sphere, cylinder };

struct RollingResistanceParams {
  RollingPart part = RollingPart::rolling;
  RollingBody body = RollingBody::sphere;
  double coefficient = 0.0;  // c (m): the level is c N (N m)
  double stiffness = 1.0;    // K (N m/rad), > 0
  double damping = 0.0;      // B (N m s/rad), >= 0
  double radius = 0.0;       // the sphere's radius: its contact point is p - radius n
};

// A cylinder's x_hat (CylinderTwistMap): [p, v, w, a], then [p_c, v_c] per rim point.
inline constexpr int kCylinderAxis = 9;
inline constexpr int kCylinderRim = 12;
inline constexpr int kCylinderInput = kCylinderRim + 6 * core::RimPoint::kPoints;

// Throws std::invalid_argument unless coefficient >= 0, K > 0, B >= 0 (finite) and radius
// >= 0: the checks every rolling or spinning element makes of its parameters.
void check_rolling_params(const RollingResistanceParams& params);

class RollingResistance final : public core::Impedance,
                                public FrictionSpring,
                                public core::ClampedFriction,
                                public core::SlipElement {
 public:
  RollingResistance(std::string name, const KikuuweContactParams& contact,
                    const RollingResistanceParams& params);
  std::string_view type() const override { return "kikuuwe_contact"; }
  int input_size() const override {
    return params_.body == RollingBody::cylinder ? kCylinderInput : 9;
  }
  int output_size() const override { return 3; }
  int state_size() const override { return dimension(); }
  std::vector<std::string> state_labels() const override;
  void initial_state(core::VecRef y) const override { y.setZero(); }
  void evaluate(double t, core::ConstVecRef x_hat, core::ConstVecRef y, double tau, core::VecRef u,
                core::VecRef y_dot) const override;
  std::vector<core::SignalInfo> signals() const override;
  void write_signals(core::ConstVecRef x_hat, core::ConstVecRef y, core::ConstVecRef u,
                     core::VecRef out) const override;
  int regime(core::ConstVecRef x_hat, core::ConstVecRef y, double tau) const override;
  // The whole output is friction: held entirely.
  void evaluate_friction_held(double /*t*/, core::ConstVecRef /*x_hat*/, core::ConstVecRef /*y*/,
                              double /*tau*/, core::ConstVecRef u_ref, core::ConstVecRef y_dot_ref,
                              core::VecRef u, core::VecRef y_dot) const override {
    u = u_ref;
    y_dot = y_dot_ref;
  }
  double friction_cap_energy(core::ConstVecRef x_hat) const override {
    const double level = params_.coefficient * contact_normal_force(x_hat);
    return level * level / params_.stiffness;
  }
  // The angular slip (world, rad/s): w_t for a sphere's rolling, (a_p.w) a_p for a
  // cylinder's, (n.w) n for spin.
  core::Vec3 slip_velocity(core::ConstVecRef x_hat) const override;
  core::Vec3 unloaded_slip(core::ConstVecRef x_hat, core::ConstVecRef y, double tau) const override;
  // N at x_hat, as the sphere's contact computes it.
  double contact_normal_force(core::ConstVecRef x_hat) const;
  const RollingResistanceParams& params() const { return params_; }

 private:
  int dimension() const {
    return params_.part == RollingPart::rolling && params_.body == RollingBody::sphere ? 2 : 1;
  }
  // The angular velocity's coordinates the element acts on: (t1.w, t2.w), (a_p.w) or (n.w).
  Eigen::Vector2d coordinates(core::ConstVecRef x_hat) const;
  // A vector of the element's coordinates (u, e) as a world vector.
  core::Vec3 world(core::ConstVecRef x_hat, core::ConstVecRef c) const;
  // A cylinder's axis projected on the plane (not normalized).
  core::Vec3 axis_in_plane(core::ConstVecRef x_hat) const;

  KikuuweContact contact_;  // the sphere's contact, for its normal force
  RollingResistanceParams params_;
};

}  // namespace stiction::components
