// A spring-damper along the line between two points (Drake's LinearSpringDamper, a MuJoCo
// tendon spring): with d = p_A - p_B (the point wiring's x_hat) and its rate v,
//   f = (K (|d| - L) + B (v . d/|d|)) d/|d|,   u = f,
// so the moving side A receives -f (pulled back towards the free length L) and B receives
// +f. Unlike SpringDamper's zero-length law, the force is central: it puts no moment about
// the line. At |d| = 0 the direction is undefined and the force is zero. No state.
// Signals: `f` (the force on the moving side, -u) and `length` (|d|).
#pragma once

#include "core/capabilities.hpp"
#include "core/impedance.hpp"

namespace stiction::components {

struct LineSpringDamperParams {
  double stiffness = 1e3;  // K (N/m)
  double damping = 0.0;    // B (Ns/m), along the line
  double length = 0.0;     // L, the free length (m)
};

class LineSpringDamper final : public core::Impedance,
                               public core::EnergyStore,
                               public core::StiffnessHint {
 public:
  LineSpringDamper(std::string name, const LineSpringDamperParams& params);
  std::string_view type() const override { return "spring_damper"; }
  int input_size() const override { return 6; }
  int output_size() const override { return 3; }
  void evaluate(double t, core::ConstVecRef x_hat, core::ConstVecRef y, double tau, core::VecRef u,
                core::VecRef y_dot) const override;
  std::vector<core::SignalInfo> signals() const override;
  void write_signals(core::ConstVecRef x_hat, core::ConstVecRef y, core::ConstVecRef u,
                     core::VecRef out) const override;
  // 0.5 K (|d| - L)^2, for the energy monitor.
  double stored_energy(core::ConstVecRef x_hat, core::ConstVecRef y) const override;

 private:
  LineSpringDamperParams params_;
};

}  // namespace stiction::components
