// Time as a state of the network: one entry s with s_dot = 1, no input, no signals, no
// energy. Components whose law depends on time through more than evaluate() (a moving
// surface's slip speed, its power, its signals are functions of x_hat alone) read s through
// their map: every RK stage then sees its own stage time s = t + T_r, which the integrator
// advances exactly.
#pragma once

#include "core/admittance.hpp"

namespace stiction::components {

class Clock final : public core::Admittance {
 public:
  explicit Clock(std::string name) : Admittance(std::move(name)) {}
  std::string_view type() const override { return "clock"; }
  int state_size() const override { return 1; }
  int input_size() const override { return 0; }
  std::vector<std::string> state_labels() const override { return {"t"}; }
  void initial_state(core::VecRef x) const override { x[0] = 0.0; }
  void derivative(core::ConstVecRef /*x*/, core::ConstVecRef /*u_hat*/,
                  core::VecRef x_dot) const override {
    x_dot[0] = 1.0;
  }
  bool affine_in_input() const override { return true; }
  std::vector<core::SignalInfo> signals() const override { return {}; }
  void write_signals(core::ConstVecRef /*x*/, core::VecRef /*out*/) const override {}
  double energy(core::ConstVecRef /*x*/) const override { return 0.0; }
};

}  // namespace stiction::components
