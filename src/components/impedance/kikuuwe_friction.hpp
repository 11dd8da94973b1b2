// Kikuuwe friction, paper eq. (19), in n dimensions (n = 1 for a joint):
//   f   = gsat(F, (B + tau K) v + K e)
//   eps = (f - K e) / (B + tau K)          (the state derivative: e_dot = eps)
// While not saturated eps == v exactly, so the anchor (position - e) does not drift.
// gsat is friction_law.hpp's: stuck up to the static level, then the Stribeck level between
// static_limit and force_limit plus viscous friction (plain gsat when static_limit =
// force_limit and viscous = 0).
// Input x_hat = [position (n), velocity (n)] of the moving side; only the velocity is used.
// Output u = f, the force the moving side exerts on the element: friction on the body is
// -f (applied by the map). Signals: tau (n = 1) or f (n > 1), and e.
#pragma once

#include "components/impedance/friction_capabilities.hpp"
#include "components/impedance/friction_law.hpp"
#include "core/impedance.hpp"

namespace stiction::components {

struct KikuuweFrictionParams {
  double stiffness = 1e4;    // K
  double damping = 1.0;      // B
  double force_limit = 1.0;  // F, the Coulomb (kinetic) level
  int dimension = 1;
  double static_limit = -1.0;      // F_s >= F, the breakaway level; < 0: equal to force_limit
  double stribeck_velocity = 0.0;  // v_s (m/s or rad/s), 0: none
  double viscous = 0.0;            // B_v (N s/m or N m s/rad), while sliding
};

// gsat(X, x) of eq. (15): x if |x| <= X, else X x / |x|. Writes the result into x.
void saturate(double limit, core::VecRef x);

// Its spring K holds 0.5 K |e|^2; it clamps at F (stuck: regime 1, sliding: 2), and its slip
// velocity is the velocity part of x_hat (so dimension <= 3).
class KikuuweFriction final : public core::Impedance,
                              public FrictionSpring,
                              public core::ClampedFriction,
                              public core::SlipElement {
 public:
  KikuuweFriction(std::string name, const KikuuweFrictionParams& params);
  std::string_view type() const override { return "kikuuwe_friction"; }
  int input_size() const override { return 2 * params_.dimension; }
  int output_size() const override { return params_.dimension; }
  int state_size() const override { return params_.dimension; }
  std::vector<std::string> state_labels() const override;
  // The friction state at t = 0 (`dimension` entries; default zeros): a preloaded spring.
  void initial_state(core::VecRef y) const override {
    if (initial_e_.size() == params_.dimension) y = initial_e_;
  }
  void set_initial_e(const core::Vec& e) { initial_e_ = e; }
  void evaluate(double t, core::ConstVecRef x_hat, core::ConstVecRef y, double tau, core::VecRef u,
                core::VecRef y_dot) const override;
  std::vector<core::SignalInfo> signals() const override;
  void write_signals(core::ConstVecRef x_hat, core::ConstVecRef y, core::ConstVecRef u,
                     core::VecRef out) const override;
  int regime(core::ConstVecRef x_hat, core::ConstVecRef y, double tau) const override {
    const int n = params_.dimension;
    const double norm =
        ((params_.damping + tau * params_.stiffness) * x_hat.segment(n, n) + params_.stiffness * y)
            .norm();
    return norm <= levels_.breakaway ? 1 : 2;
  }
  core::Vec3 slip_velocity(core::ConstVecRef x_hat) const override;
  double static_ratio() const override {
    return levels_.kinetic > 0.0 && levels_.breakaway > levels_.kinetic
               ? levels_.breakaway / levels_.kinetic
               : 1.0;
  }
  // The whole output is friction: held entirely.
  void evaluate_friction_held(double /*t*/, core::ConstVecRef /*x_hat*/, core::ConstVecRef /*y*/,
                              double /*tau*/, core::ConstVecRef u_ref, core::ConstVecRef y_dot_ref,
                              core::VecRef u, core::VecRef y_dot) const override {
    u = u_ref;
    y_dot = y_dot_ref;
  }
  double friction_cap_energy(core::ConstVecRef /*x_hat*/) const override {
    return levels_.breakaway * levels_.breakaway / params_.stiffness;
  }
  core::Vec3 unloaded_slip(core::ConstVecRef /*x_hat*/, core::ConstVecRef y,
                           double tau) const override {
    core::Vec3 v = core::Vec3::Zero();
    v.head(params_.dimension) =
        -params_.stiffness / (params_.damping + tau * params_.stiffness) * y;
    return v;
  }
  const KikuuweFrictionParams& params() const { return params_; }
  const FrictionLevels& levels() const { return levels_; }

 private:
  KikuuweFrictionParams params_;
  FrictionLevels levels_;
  core::Vec initial_e_;
};

}  // namespace stiction::components
