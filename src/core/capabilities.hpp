// Capabilities an impedance may have beyond evaluating its law, each a small interface of its
// own (as NormalContact in contact.hpp): a component inherits the ones it implements, and
// the network resolves them once when it is finalized (Network::capabilities), so that the
// stability analysis, the energy monitor and the event detection ask the elements that
// have a capability and nobody else. None of them is on the derivative's path.
#pragma once

#include <limits>

#include "core/contact.hpp"
#include "core/impedance.hpp"
#include "core/types.hpp"

namespace stiction::core {

// Potential energy held in the element's springs (a contact, a friction spring), so that the
// energy monitor sees the total.
class EnergyStore {
 public:
  virtual ~EnergyStore() = default;
  virtual double stored_energy(ConstVecRef x_hat, ConstVecRef y) const = 0;
};

// An energy source (a prescribed torque, a moving surface): the energy monitor allows the
// network energy to grow by what the sources put in, and no more.
class Source {
 public:
  virtual ~Source() = default;
  // Power fed into the admittances at (x_hat, u).
  virtual double power_in(ConstVecRef x_hat, ConstVecRef u) const = 0;
  // True for a feedback law, whose output reads the state (a PD controller): a spring or
  // damper in disguise, whose work the energy monitor cannot take as put in from outside
  // (core/feedback_monitor.hpp). False for a source driven by time alone.
  virtual bool reads_state() const { return false; }
};

// A sliding pair (contacts, joint friction): stick/slip events are detected on its slip
// velocity at every step, not only at output samples.
class SlipElement {
 public:
  virtual ~SlipElement() = default;
  // Relative velocity of the pair at input x_hat (a joint uses the x entry).
  virtual Vec3 slip_velocity(ConstVecRef x_hat) const = 0;
  // The static friction level over the kinetic one (mu_static / mu, static_limit /
  // force_limit): above 1, every slip onset from a stick is a breakaway at the static level,
  // which the run's summary names (`first_breakaway`, io/summary.cpp). 1 for a law with one
  // level.
  virtual double static_ratio() const { return 1.0; }
};

// A law with smooth pieces: which one the element is on at (x_hat, y; tau), e.g. 0 open,
// 1 stuck, 2 sliding for a contact. Linear stability analysis is only meaningful while no
// element changes piece during a step; elements without this capability are smooth.
class PiecewiseLaw {
 public:
  virtual ~PiecewiseLaw() = default;
  virtual int regime(ConstVecRef x_hat, ConstVecRef y, double tau) const = 0;
};

// Friction clamped at a limit force (Kikuuwe's model; regime 1 stuck, 2 sliding). While such
// an element sticks, its spring can carry a numerical oscillation, but that one cannot run
// away: it ends where the force reaches the limit and the element slides. Stability analysis
// tells these modes apart by linearizing once more with the friction held:
// - evaluate_friction_held(): Impedance::evaluate() with the friction force and the
//   friction-state rate taken from a reference evaluation (u_ref, y_dot_ref), the rest (a
//   contact's normal force) live;
// - friction_cap_energy(): the most energy such a bounded oscillation holds, taken as
//   twice the spring's energy at the limit force, F^2 / K (spring plus motion).
class ClampedFriction : public PiecewiseLaw {
 public:
  virtual void evaluate_friction_held(double t, ConstVecRef x_hat, ConstVecRef y, double tau,
                                      ConstVecRef u_ref, ConstVecRef y_dot_ref, VecRef u,
                                      VecRef y_dot) const = 0;
  virtual double friction_cap_energy(ConstVecRef x_hat) const = 0;
  // The slip velocity at which the law's force before clamping is zero, -K e / (B + tau K),
  // in the frame slip_velocity() uses: the middle of the band of slip velocities in which the
  // element holds. An implicit step whose Newton iteration reverses a sliding element's slip
  // puts it there first (core/implicit_euler.hpp).
  virtual Vec3 unloaded_slip(ConstVecRef x_hat, ConstVecRef y, double tau) const = 0;
};

// The largest |y| (max over the entries) the exact model keeps from an initial state within
// it (LuGre and Dahl bristles: |e| <= F / K). A numerical instability whose error dissipates
// does not grow the energy, but it drives such a state past its bound, so the run's monitor
// checks it too. A value the element states once.
class BoundedState {
 public:
  explicit BoundedState(double bound) : state_bound_(bound) {}
  double state_bound() const { return state_bound_; }

 private:
  double state_bound_;
};

// Largest stiffness the element puts between its ports (N/m or Nm/rad) and the damping beside
// it (NaN where it has none to name), for stability advice (`stiction check`) and for the
// natural size of a clamped friction state. Values the element states once.
class StiffnessHint {
 public:
  explicit StiffnessHint(double stiffness,
                         double damping = std::numeric_limits<double>::quiet_NaN())
      : stiffness_(stiffness), damping_(damping) {}
  double stiffness() const { return stiffness_; }
  double damping() const { return damping_; }

 private:
  double stiffness_, damping_;
};

// One impedance's capabilities (null where it has none), found by dynamic_cast: done once per
// element (Network::finalize keeps the result), never per step.
struct Capabilities {
  const EnergyStore* energy = nullptr;
  const Source* source = nullptr;
  const SlipElement* slip = nullptr;
  const PiecewiseLaw* law = nullptr;
  const ClampedFriction* friction = nullptr;
  const BoundedState* bound = nullptr;
  const StiffnessHint* stiffness = nullptr;
  const NormalContact* contact = nullptr;
};

inline Capabilities capabilities_of(const Impedance& impedance) {
  return {dynamic_cast<const EnergyStore*>(&impedance),
          dynamic_cast<const Source*>(&impedance),
          dynamic_cast<const SlipElement*>(&impedance),
          dynamic_cast<const PiecewiseLaw*>(&impedance),
          dynamic_cast<const ClampedFriction*>(&impedance),
          dynamic_cast<const BoundedState*>(&impedance),
          dynamic_cast<const StiffnessHint*>(&impedance),
          dynamic_cast<const NormalContact*>(&impedance)};
}

}  // namespace stiction::core
