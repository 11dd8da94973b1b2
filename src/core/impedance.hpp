// Impedance component (paper eqs. 9 and 22): motion in, force out,
// [u, y_dot] = I(x_hat, y; tau). x_hat comes from the component's coordinate map (Psi),
// u goes back through the same map (Phi). Convention (DESIGN section 1): u is the force
// that the moving side exerts on the element, so the map applies -u to that side.
// tau is the stage step size T_r of the generalized Runge-Kutta method; t is the stage
// time, used by source elements whose output is a function of time.
#pragma once

#include <limits>
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

  // Which smooth piece of its law the element is on at (x_hat, y; tau): e.g. 0 open,
  // 1 stuck, 2 sliding for a contact. Linear stability analysis is only meaningful while no
  // element changes regime during a step; smooth elements return 0.
  virtual int regime(ConstVecRef /*x_hat*/, ConstVecRef /*y*/, double /*tau*/) const { return 0; }

  // Friction clamped at a limit force (Kikuuwe's model). While such an element sticks, its
  // spring can carry a numerical oscillation, but that one cannot run away: it ends where
  // the force reaches the limit and the element slides. Stability analysis tells these
  // modes apart by linearizing once more with the friction held:
  // - evaluate_friction_held(): evaluate() with the friction force and the friction-state
  //   rate taken from a reference evaluation (u_ref, y_dot_ref), the rest (a contact's
  //   normal force) live;
  // - friction_cap_energy(): the most energy such a bounded oscillation holds, taken as
  //   twice the spring's energy at the limit force, F^2 / K (spring plus motion).
  virtual bool clamps_friction() const { return false; }
  virtual void evaluate_friction_held(double t, ConstVecRef x_hat, ConstVecRef y, double tau,
                                      ConstVecRef /*u_ref*/, ConstVecRef /*y_dot_ref*/, VecRef u,
                                      VecRef y_dot) const {
    evaluate(t, x_hat, y, tau, u, y_dot);
  }
  virtual double friction_cap_energy(ConstVecRef /*x_hat*/) const { return 0.0; }

  // The largest |y| (max over the entries) the exact model keeps from an initial state within
  // it, where it has one (LuGre and Dahl bristles: |e| <= F / K); infinity otherwise. A
  // numerical instability whose error dissipates does not grow the energy, but it drives
  // such a state past its bound, so the run's monitor checks it too.
  virtual double state_bound() const { return std::numeric_limits<double>::infinity(); }

  // Power this element feeds into the admittances at (x_hat, u), for elements that are
  // energy sources (prescribed torques); passive elements return 0. The energy monitor
  // allows the network energy to grow by what the sources put in, and no more.
  virtual bool is_source() const { return false; }
  // Potential energy held in the element's springs (contact, friction spring), so that
  // the energy monitor sees the total; 0 for elements that store none.
  virtual double stored_energy(ConstVecRef /*x_hat*/, ConstVecRef /*y*/) const { return 0.0; }
  virtual double power_in(ConstVecRef /*x_hat*/, ConstVecRef /*u*/) const { return 0.0; }

  // Largest stiffness this element puts between its ports (N/m or Nm/rad), and the
  // damping beside it (NaN where the element has none to name), for stability advice; then
  // the event signals it offers, for event detection.
  virtual double stiffness() const { return 0.0; }
  virtual double damping() const { return std::numeric_limits<double>::quiet_NaN(); }
  // Whether this element has a slip speed (contacts, joint friction): stick/slip events
  // are detected on it at every step, not only at output samples.
  virtual bool has_slip() const { return false; }
  // Relative velocity of the sliding pair at input x_hat (a joint uses the x entry);
  // only called when has_slip().
  virtual Vec3 slip_velocity(ConstVecRef /*x_hat*/) const { return Vec3::Zero(); }

 private:
  std::string name_;
};

}  // namespace stiction::core
