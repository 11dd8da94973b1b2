// One-sided stop at the ends of a joint's travel (a URDF <limit lower upper>): with q the
// joint coordinate and qd its rate,
//   u = K (q - upper) + B qd   when q > upper,
//   u = K (q - lower) + B qd   when q < lower,
//   u = 0                      inside [lower, upper].
// The damping acts only while the joint is past a limit, and the stop never pulls: its
// force is clamped to the side that pushes the joint back (u >= 0 above, u <= 0 below), so
// a joint leaving the stop fast is released, not held (no "sticky" wall).
// Input x_hat = [q, qd]; output u, the torque (force) the joint exerts on the stop (the
// joint receives -u, DESIGN section 1). Signal `tau`: -u. Either limit may be infinite.
#pragma once

#include <limits>

#include "core/capabilities.hpp"
#include "core/impedance.hpp"

namespace stiction::components {

struct JointLimitParams {
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
  double stiffness = 1e4;  // K (Nm/rad or N/m)
  double damping = 1.0;    // B (Nms/rad or Ns/m): small, explicit (light wrist links)
};

class JointLimit final : public core::Impedance,
                         public core::EnergyStore,
                         public core::StiffnessHint {
 public:
  JointLimit(std::string name, const JointLimitParams& params);
  std::string_view type() const override { return "joint_limit"; }
  int input_size() const override { return 2; }
  int output_size() const override { return 1; }
  void evaluate(double t, core::ConstVecRef x_hat, core::ConstVecRef y, double tau, core::VecRef u,
                core::VecRef y_dot) const override;
  std::vector<core::SignalInfo> signals() const override;
  void write_signals(core::ConstVecRef x_hat, core::ConstVecRef y, core::ConstVecRef u,
                     core::VecRef out) const override;
  // 0.5 K (penetration)^2.
  double stored_energy(core::ConstVecRef x_hat, core::ConstVecRef y) const override;
  const JointLimitParams& params() const { return params_; }

 private:
  // How far q is past the nearer limit (signed: > 0 above upper, < 0 below lower), else 0.
  double penetration(double q) const;
  JointLimitParams params_;
};

}  // namespace stiction::components
