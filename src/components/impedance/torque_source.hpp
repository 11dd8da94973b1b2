// A prescribed generalized force as a function of time (the paper's motor torques,
// eqs. 28c-28d): an impedance with no state whose output ignores the motion. The value is
// given by a callable so that core stays free of the expression parser.
// Output u = -value, so that the driven side receives +value. Signal: tau (the value).
#pragma once

#include <functional>

#include "core/impedance.hpp"

namespace stiction::components {

class TorqueSource final : public core::Impedance {
 public:
  using Profile = std::function<double(double t)>;
  // dimension: size of the generalized force; one profile per entry.
  TorqueSource(std::string name, std::vector<Profile> profiles, std::string signal_name = "tau");
  std::string_view type() const override { return "torque_source"; }
  int input_size() const override { return 2 * static_cast<int>(profiles_.size()); }
  int output_size() const override { return static_cast<int>(profiles_.size()); }
  void evaluate(double t, core::ConstVecRef x_hat, core::ConstVecRef y, double tau, core::VecRef u,
                core::VecRef y_dot) const override;
  std::vector<core::SignalInfo> signals() const override;
  bool is_source() const override { return true; }
  // The driven side receives -u while moving at the velocity half of x_hat.
  double power_in(core::ConstVecRef x_hat, core::ConstVecRef u) const override {
    return -u.dot(x_hat.tail(u.size()));
  }
  void write_signals(core::ConstVecRef x_hat, core::ConstVecRef y, core::ConstVecRef u,
                     core::VecRef out) const override;

 private:
  std::vector<Profile> profiles_;
  std::string signal_name_;
};

}  // namespace stiction::components
