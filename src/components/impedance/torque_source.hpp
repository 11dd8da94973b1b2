// A prescribed generalized force (the paper's motor torques, eqs. 28c-28d; a force on a body
// point): an impedance with no state whose output ignores the motion it is wired to. Each
// entry is given by a callable, so that core stays free of the expression parser.
//
// Input x_hat = [position (n), velocity (n), observed (m)]: the motion of what it drives
// (its map's Psi) followed by m observed entries (gathered from the stage state by an
// ObservingMap); an Observer turns them into the values the callables receive (signals of
// the scene, some of them other elements evaluated at the stage), or they are the values
// themselves. A feedback law (PD controller) is a source of this kind, evaluated at every
// integrator stage from the stage state.
// Output u = -value, so that the driven side receives +value. Signal: `tau` or `f` (the
// value). It is an energy source: power_in() is what it feeds to the driven side.
#pragma once

#include <functional>
#include <string>

#include "core/capabilities.hpp"
#include "core/impedance.hpp"

namespace stiction::components {

class TorqueSource final : public core::Impedance, public core::Source {
 public:
  using Profile = std::function<double(double t)>;
  // Value at time t from the m observed values.
  using StateProfile = std::function<double(double t, const double* observed)>;
  // The values the profiles read, from the m observed entries of x_hat at (t, tau).
  using Observer = std::function<const double*(double t, double tau, const double* observed)>;
  // One profile per entry of the generalized force; no observed values.
  TorqueSource(std::string name, std::vector<Profile> profiles, std::string signal_name = "tau");
  // `observed`: m, the number of observed entries after the motion in x_hat. `type`:
  // "torque_source" or "force_source" (for messages and `stiction check`). No observer: the
  // profiles read the observed entries as they are.
  TorqueSource(std::string name, std::vector<StateProfile> profiles, int observed,
               std::string signal_name, std::string type, Observer observer = {});
  std::string_view type() const override { return type_; }
  int input_size() const override { return 2 * size() + observed_; }
  int output_size() const override { return size(); }
  void evaluate(double t, core::ConstVecRef x_hat, core::ConstVecRef y, double tau, core::VecRef u,
                core::VecRef y_dot) const override;
  std::vector<core::SignalInfo> signals() const override;
  // The driven side receives -u while moving at the velocity part of x_hat.
  double power_in(core::ConstVecRef x_hat, core::ConstVecRef u) const override {
    return -u.dot(x_hat.segment(size(), size()));
  }
  // A feedback law when it observes signals of the scene.
  bool reads_state() const override { return observed_ > 0; }
  void write_signals(core::ConstVecRef x_hat, core::ConstVecRef y, core::ConstVecRef u,
                     core::VecRef out) const override;

 private:
  int size() const { return static_cast<int>(profiles_.size()); }
  std::vector<StateProfile> profiles_;
  int observed_ = 0;
  Observer observer_;
  std::string signal_name_;
  std::string type_;
};

}  // namespace stiction::components
