// Dahl friction, paper eq. (11), one dimension (a joint or a slider):
//   u = K e,   e_dot = v - |v| K e / F
// e is the elastic (pre-sliding) displacement; while sliding at constant v, e relaxes to
// sgn(v) F / K, so u tends to F sgn(v). Input x_hat = [position, velocity] of the moving
// side; only the velocity is used. Unlike eq. (19) the rate does not depend on the stage
// size tau: Dahl is an ordinary ODE. It creeps under sub-Coulomb forces that change sign of
// v (no true static friction).
// Sign convention (DESIGN section 1): u is the force the moving side exerts on the element,
// so the body receives -u (opposite to its velocity while sliding).
// Signals: tau = -u (the torque/force on the driven side), e.
#pragma once

#include "components/impedance/friction_capabilities.hpp"
#include "core/impedance.hpp"

namespace stiction::components {

struct DahlParams {
  double stiffness = 1e4;    // K (N/m or Nm/rad)
  double force_limit = 1.0;  // F > 0, the kinetic (Coulomb) level
  double initial_e = 0.0;
};

// A friction spring (0.5 K e^2) with stick/slip events on the sliding velocity; e_dot <= 0
// at e = F / K while v > 0 (and the mirror for v < 0), so |e| <= F / K.
class Dahl final : public core::Impedance,
                   public FrictionSpring,
                   public JointSlip,
                   public core::BoundedState {
 public:
  Dahl(std::string name, const DahlParams& params);
  std::string_view type() const override { return "dahl"; }
  int input_size() const override { return 2; }
  int output_size() const override { return 1; }
  int state_size() const override { return 1; }
  std::vector<std::string> state_labels() const override { return {"e"}; }
  void initial_state(core::VecRef y) const override { y[0] = params_.initial_e; }
  void evaluate(double t, core::ConstVecRef x_hat, core::ConstVecRef y, double tau, core::VecRef u,
                core::VecRef y_dot) const override;
  std::vector<core::SignalInfo> signals() const override;
  void write_signals(core::ConstVecRef x_hat, core::ConstVecRef y, core::ConstVecRef u,
                     core::VecRef out) const override;
  const DahlParams& params() const { return params_; }

 private:
  DahlParams params_;
};

}  // namespace stiction::components
