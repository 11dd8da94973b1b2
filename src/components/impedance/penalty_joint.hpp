// Penalty-based revolute joint (paper Simulation III, eq. 29) between a child and a parent
// articulation frame, with Kikuuwe friction (19) about the joint axis. Input x_hat (26) from
// a FramePairMap: [child frame, parent frame], each [p, v, q (w x y z), w_world]. State e.
//
// With a_c = q_c axis_child and a_p = q_p axis_parent the joint axes in the world,
// n = (a_c + a_p) / |a_c + a_p| the mean axis and w_rel = w_c - w_p:
//   separation  f      = Ks (p_c - p_p) + Bs (v_c - v_p)
//   bending     t_bend = Kb phi (a_p x a_c) / |a_p x a_c| + Bb (w_rel - (n.w_rel) n)
//               (phi = angle between the axes; equal to Kb (a_p x a_c) for small angles, but
//               keeps restoring up to 180 degrees)
//   friction    s = (Bf + tau Kf) omega + Kf e,  omega = n.w_rel
//               f_F = gsat(F, s),  e_dot = eps = (f_F - Kf e) / (Bf + tau Kf)
//               (eps == omega exactly while |s| <= F: a stuck joint does not creep)
//   u = [f, t_bend + f_F n]
// Sign convention (DESIGN section 1): u is the wrench the child exerts on the element; the
// child receives -u (force at its point, free torque), the parent +u. Bending and friction
// torques are perpendicular and parallel to n respectively, so n.u_torque = f_F exactly.
// The separation force is applied at each body's own point; the pair is then not exactly
// moment-free (d x f with d the separation), an O(|d|) error that the stiffness keeps small.
// Signals: theta (rotation of the child relative to the parent about axis_parent, measured
// from `reference`, reported in [-pi, pi) and unwrapped by the recorder), omega, tau (friction
// torque on the child about n, i.e. -f_F) and e.
#pragma once

#include "core/capabilities.hpp"
#include "core/impedance.hpp"

namespace stiction::components {

struct PenaltyJointParams {
  core::Vec3 axis_child{0.0, 0.0, 1.0};   // joint axis in the child's body frame
  core::Vec3 axis_parent{0.0, 0.0, 1.0};  // in the parent's frame (world for the ground)
  double separation_stiffness = 1e6;      // Ks (N/m)
  double separation_damping = 200.0;      // Bs (N s/m)
  double bending_stiffness = 1e3;         // Kb (N m/rad)
  double bending_damping = 0.01;          // Bb (N m s/rad)
  // Friction (19) about the axis. F = 0 (the default) makes the joint frictionless.
  double friction_stiffness = 5000.0;  // Kf (N m/rad)
  double friction_damping = 1.0;       // Bf (N m s/rad)
  double friction_limit = 0.0;         // F (N m)
  // Orientation of the child relative to the parent (q_p^-1 q_c) at which theta = 0, and an
  // angle added to theta (e.g. the initial joint angle when the reference is the identity).
  core::Quat reference = core::Quat::Identity();
  double angle_offset = 0.0;
  double initial_e = 0.0;
};

// Stick/slip events of its friction about the axis, the energy of its three springs, and its
// separation stiffness for stability advice. Its friction is Kikuuwe's law, so it is a
// ClampedFriction like kikuuwe_friction: the event detector asks it for its regime (1 stuck,
// 2 sliding) and times a stick exactly even while the joint rings elastically inside its
// friction band; the stability analysis holds its friction torque to tell a stuck spring's
// bounded chatter from a runaway.
class PenaltyJoint final : public core::Impedance,
                           public core::EnergyStore,
                           public core::SlipElement,
                           public core::ClampedFriction,
                           public core::StiffnessHint {
 public:
  PenaltyJoint(std::string name, const PenaltyJointParams& params);
  std::string_view type() const override { return "penalty_joint"; }
  int input_size() const override { return 26; }
  int output_size() const override { return 6; }
  int state_size() const override { return 1; }
  std::vector<std::string> state_labels() const override { return {"e"}; }
  void initial_state(core::VecRef y) const override { y[0] = params_.initial_e; }
  void evaluate(double t, core::ConstVecRef x_hat, core::ConstVecRef y, double tau, core::VecRef u,
                core::VecRef y_dot) const override;
  std::vector<core::SignalInfo> signals() const override;
  void write_signals(core::ConstVecRef x_hat, core::ConstVecRef y, core::ConstVecRef u,
                     core::VecRef out) const override;
  // 0.5 (Ks |d|^2 + Kb phi^2 + Kf e^2): separation, bending and friction springs.
  double stored_energy(core::ConstVecRef x_hat, core::ConstVecRef y) const override;
  // 1 while the friction about the axis is stuck, 2 while it slides.
  int regime(core::ConstVecRef x_hat, core::ConstVecRef y, double tau) const override;
  // Separation and bending live; the friction torque about the axis and e's rate held at the
  // reference evaluation's. The reference's axis n_ref is not passed in, so the held torque
  // is n.u_ref (n the live axis): exact for n = n_ref, and off by (n - n_ref).t_bend_ref, a
  // geometric term of the bending torque, not of the friction spring.
  void evaluate_friction_held(double t, core::ConstVecRef x_hat, core::ConstVecRef y, double tau,
                              core::ConstVecRef u_ref, core::ConstVecRef y_dot_ref, core::VecRef u,
                              core::VecRef y_dot) const override;
  // Twice the friction spring's energy at the limit: F^2 / Kf.
  double friction_cap_energy(core::ConstVecRef /*x_hat*/) const override {
    return params_.friction_limit * params_.friction_limit / params_.friction_stiffness;
  }
  // The relative rate about the axis (in the x entry, as for joints).
  core::Vec3 slip_velocity(core::ConstVecRef x_hat) const override;
  core::Vec3 unloaded_slip(core::ConstVecRef /*x_hat*/, core::ConstVecRef y,
                           double tau) const override {
    const double kf = params_.friction_stiffness;
    return {-kf / (params_.friction_damping + tau * kf) * y[0], 0.0, 0.0};
  }
  const PenaltyJointParams& params() const { return params_; }

  // Relative rotation angle about the axis in [-pi, pi), from an input x_hat.
  double relative_angle(core::ConstVecRef x_hat) const;

 private:
  PenaltyJointParams params_;
  core::Quat reference_inverse_;
};

}  // namespace stiction::components
