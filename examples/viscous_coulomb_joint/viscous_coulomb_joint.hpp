// A joint impedance written outside stiction: Kikuuwe's Coulomb friction (paper eq. 19) in
// parallel with a viscous damper b,
//   f_c = sat_F((B + tau K) v + K e),   e_dot = (f_c - K e) / (B + tau K),   u = f_c + b v,
// with x_hat = [theta, omega] of one joint (v = omega) and state e. u is the torque the
// moving side exerts on the element (DESIGN section 1): the joint receives -u. While the
// Coulomb part is not saturated, e_dot == v exactly, so a stuck joint does not drift.
#pragma once

#include <stiction/components/impedance/friction_capabilities.hpp>
#include <stiction/core/capabilities.hpp>
#include <stiction/core/impedance.hpp>

namespace example {

struct ViscousCoulombParams {
  double stiffness = 5000.0;  // K, Nm/rad
  double damping = 1.0;       // B, Nms/rad (of the friction spring)
  double coulomb = 0.5;       // F, Nm
  double viscous = 0.2;       // b, Nms/rad
};

// Beyond its law it offers two capabilities (stiction/core/capabilities.hpp): a slip velocity,
// the joint's rate (JointSlip: stick/slip events), and a stiffness for `stiction check`'s
// advice (StiffnessHint, stated at construction).
class ViscousCoulombJoint final : public stiction::core::Impedance,
                                  public stiction::components::JointSlip,
                                  public stiction::core::StiffnessHint {
 public:
  ViscousCoulombJoint(std::string name, const ViscousCoulombParams& params);
  std::string_view type() const override { return "viscous_coulomb_joint"; }
  int input_size() const override { return 2; }
  int output_size() const override { return 1; }
  int state_size() const override { return 1; }
  std::vector<std::string> state_labels() const override { return {"e"}; }
  void evaluate(double t, stiction::core::ConstVecRef x_hat, stiction::core::ConstVecRef y, double tau,
                stiction::core::VecRef u, stiction::core::VecRef y_dot) const override;
  std::vector<stiction::core::SignalInfo> signals() const override;
  void write_signals(stiction::core::ConstVecRef x_hat, stiction::core::ConstVecRef y,
                     stiction::core::ConstVecRef u, stiction::core::VecRef out) const override;

 private:
  ViscousCoulombParams params_;
};

}  // namespace example
