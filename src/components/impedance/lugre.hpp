// LuGre friction, paper eq. (12), one dimension:
//   e_dot = v - |v| e / g(v)
//   u     = K e + B e_dot + D v
//   g(v)  = (F + (Fs - F) exp(-(v/vs)^2)) / K   with a Stribeck effect (Fs, vs set),
//   g(v)  = F / K                                 without (the default).
// K is sigma0 (bristle stiffness), B sigma1 (bristle damping), D sigma2 (viscous). While
// sliding at constant v, e relaxes to sgn(v) g(v) and u tends to sgn(v) K g(v) + D v.
// Input x_hat = [position, velocity] of the moving side; only the velocity is used. Like
// Dahl it is an ordinary ODE (tau unused) and drifts under oscillating sub-Coulomb forces.
// Sign convention (DESIGN section 1): u is the force the moving side exerts on the element;
// the body receives -u.
// Signals: tau = -u (on the driven side), e.
#pragma once

#include <algorithm>

#include "components/impedance/friction_capabilities.hpp"
#include "core/impedance.hpp"

namespace stiction::components {

struct LuGreParams {
  double stiffness = 1e4;    // K = sigma0
  double damping = 1.0;      // B = sigma1
  double viscous = 0.0;      // D = sigma2
  double force_limit = 1.0;  // F > 0, Coulomb level
  // Stribeck effect: static level Fs and velocity vs; disabled while vs <= 0.
  double static_limit = 0.0;       // Fs
  double stribeck_velocity = 0.0;  // vs
  double initial_e = 0.0;
};

// A friction spring (the bristle, 0.5 K e^2) with stick/slip events on the sliding
// velocity; e_dot <= 0 at e = max g, so the bristle never bends further than the highest
// steady deflection (the state bound).
class LuGre final : public core::Impedance,
                    public FrictionSpring,
                    public JointSlip,
                    public core::BoundedState {
 public:
  LuGre(std::string name, const LuGreParams& params);
  std::string_view type() const override { return "lugre"; }
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
  const LuGreParams& params() const { return params_; }

  // g(v) above (a displacement: the steady bristle deflection while sliding at v).
  double steady_deflection(double v) const;

 private:
  LuGreParams params_;
};

}  // namespace stiction::components
