// Impedance component (paper eqs. 9 and 22): motion in, force out,
// [u, y_dot] = I(x_hat, y; tau). x_hat comes from the component's coordinate map (Psi),
// u goes back through the same map (Phi). Convention (DESIGN section 1): u is the force
// that the moving side exerts on the element, so the map applies -u to that side.
// tau is the stage step size T_r of the generalized Runge-Kutta method; t is the stage
// time, used by source elements whose output is a function of time.
// Only what every element has is here; what some have (stored energy, a slip velocity, a
// friction that clamps, ...) are capability interfaces of their own (core/capabilities.hpp).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/signal.hpp"
#include "core/types.hpp"

namespace stiction::core {

class Impedance {
 public:
  explicit Impedance(std::string name) : name_(std::move(name)) {}
  virtual ~Impedance() = default;
  Impedance(const Impedance&) = delete;
  Impedance& operator=(const Impedance&) = delete;

  const std::string& name() const { return name_; }
  virtual std::string_view type() const = 0;

  virtual int input_size() const = 0;   // size of x_hat
  virtual int output_size() const = 0;  // size of u
  virtual int state_size() const { return 0; }
  virtual std::vector<std::string> state_labels() const { return {}; }
  virtual void initial_state(VecRef /*y*/) const {}

  virtual void evaluate(double t, ConstVecRef x_hat, ConstVecRef y, double tau, VecRef u,
                        VecRef y_dot) const = 0;

  // Signals are written from the values of one evaluation at the current state.
  virtual std::vector<SignalInfo> signals() const = 0;
  virtual void write_signals(ConstVecRef x_hat, ConstVecRef y, ConstVecRef u,
                             VecRef out) const = 0;

 private:
  std::string name_;
};

}  // namespace stiction::core
