// What the run's energy monitor allows the network energy to do (issue 26, item 2). Passive
// elements only store or dissipate, so the network energy minus the work the sources put in
// can only fall: every rise of E - W above the lowest value it has had is the integrator's
// doing, whatever its size. It is called an instability once it exceeds
//   tolerance * scale + rounding,
// where the scale is the energy the scene actually moves around, not its absolute level:
//   scale    = the largest kinetic energy plus spring energy seen so far
//              (admittances' kinetic energy; what contacts, friction springs and springs
//              store) + the work the sources have put in so far;
//   rounding = 1e4 * eps * the largest sum of |component energies| seen so far.
// Potential energy of gravity enters only the rounding term: a block resting on a slope at
// z = 1000 m gets the same bound as at z = 0 (up to rounding of m g z, ~1e-9 of it), and a
// falling body's bound grows with the speed it gains. `tolerance` is
// RunOptions::energy_tolerance ([simulation] energy_tolerance, default 0.01).
//
// The tolerance is widened by 1/k of the scale at the k-th step: a first-order method started
// from rest has gained KE/k after k steps (explicit Euler's first step adds speed but no fall:
// a body falling from rest has v_k = g k T but has fallen only g T^2 k (k - 1) / 2, so E - W
// has risen by m g^2 T^2 k / 2 against the KE m g^2 T^2 k^2 / 2), an error of 1/k of all the
// energy moved so far that no a-posteriori scale can absorb. It was 1/(2k) for the first 64
// steps and none after, which stopped explicit Euler on a free fall at its first step, and
// again at its 65th (1/65 > 1%). A runaway grows geometrically and passes that widened bound
// within a few steps, so a short run with a large step is still caught (a run of 10 steps has
// no window to hide in). The headroom (below) ignores the widening, as chatter outlasts it,
// and the step prediction judges a state of the first kSettleObservations steps by the
// headroom at that step (core/stability.cpp).
//
// The same budget gives the stability prediction its headroom (core/stability.cpp), so that
// a stuck friction's chatter counts as an instability exactly where the monitor stops it.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/network.hpp"

namespace stiction::core {

// The kinetic, spring and absolute energies of a state.
struct EnergyParts {
  double total = 0.0;     // Network::energy: kinetic + potential + stored
  double kinetic = 0.0;   // admittances' energy minus the same with velocities zeroed
  double stored = 0.0;    // impedances' springs
  double absolute = 0.0;  // sum of |component energy|: what rounding acts on
};

inline constexpr long kSettleObservations = 64;

// The widening of the tolerance (a fraction of the scale) at the k-th step: 1/k.
inline double settling_allowance(long k) { return k >= 1 ? 1.0 / static_cast<double>(k) : 0.0; }

class EnergyBudget {
 public:
  EnergyBudget(Network& network, double tolerance) : network_(network), tolerance_(tolerance) {
    const auto& positions = network.position_slots();
    Eigen::Index largest = 0;
    for (std::size_t j = 0; j < network.admittances().size(); ++j) {
      const Slot s = network.admittance_slot(static_cast<int>(j));
      AdmittanceSlots a{s.state_offset, s.state_size, {}};
      for (int k = 0; k < s.state_size; ++k) {
        if (!positions[static_cast<std::size_t>(s.state_offset + k)]) a.velocities.push_back(k);
      }
      admittance_slots_.push_back(std::move(a));
      largest = std::max<Eigen::Index>(largest, s.state_size);
    }
    scratch_.resize(largest);
  }

  // The state x reached with `work` put in by the sources so far (the work credited).
  void observe(const Vec& x, double work) {
    const EnergyParts e = parts(x);
    energy_ = e.total;
    ++observations_;
    // A finite state whose energy is not finite (a speed of 1e191 m/s squares to inf) has
    // overflowed: inf - inf is NaN and every comparison with it is false, which let such a run
    // end `ok` (issue 25). Once the energy has been finite, losing it is an instability; a
    // component that defines no energy (NaN from the start) leaves the run unmonitored.
    const bool finite = std::isfinite(e.total) && std::isfinite(e.kinetic + e.stored) &&
                        std::isfinite(e.absolute) && std::isfinite(e.total - work);
    if (!finite) {
      overflowed_ = overflowed_ || defined_ || std::isinf(e.total) || std::isinf(e.absolute);
      return;
    }
    defined_ = true;
    moved_ = std::max(moved_, e.kinetic + e.stored);
    absolute_ = std::max(absolute_, e.absolute);
    work_ = std::max(work_, work);
    floor_ = std::min(floor_, e.total - work);
    rise_ = e.total - work - floor_;
  }
  // The energy at the last observed state (NaN if a component defines none).
  double energy() const { return energy_; }
  bool monitored() const { return std::isfinite(energy_) && std::isfinite(floor_); }
  // The energy (or the scale it is measured against) stopped being a finite number.
  bool overflowed() const { return overflowed_; }
  double scale() const { return moved_ + work_; }
  double rounding() const { return 1e4 * std::numeric_limits<double>::epsilon() * absolute_; }
  // How far E - W may rise above its lowest value before the run is called unstable.
  double allowed() const { return tolerance_ * scale() + rounding(); }
  // E - W above its lowest value so far, at the last observed state.
  double rise() const { return rise_; }
  double headroom() const { return monitored() ? allowed() - rise_ : INFINITY; }
  bool exceeded() const {
    // The first observation is the initial state: the k-th step is observation k + 1.
    const double settling = settling_allowance(observations_ - 1);
    if (overflowed_) return true;
    const double bound = allowed() + settling * scale();
    return monitored() && (rise_ > bound || !std::isfinite(bound));
  }

 private:
  // The run's monitor observes every step (issue 26), so this pass is on the run loop's
  // per-step path: each admittance's energy is evaluated once at x and once with its
  // velocities zeroed (in a scratch of the admittance's own size), and the total is their sum
  // continued by the impedances' stored energies, the same additions in the same order as
  // Network::energy (issue 24: the monitor had evaluated every admittance three times, the
  // whole state copied, 1000 instructions of a sphere_roll step's 4900).
  EnergyParts parts(const Vec& x) {
    EnergyParts e;
    double admittances = 0.0;
    const auto& list = network_.admittances();
    for (std::size_t j = 0; j < list.size(); ++j) {
      const AdmittanceSlots& a = admittance_slots_[j];
      const auto own = x.segment(a.offset, a.size);
      auto at_rest_state = scratch_.head(a.size);
      at_rest_state = own;
      for (int k : a.velocities) at_rest_state[k] = 0.0;
      const double full = list[j]->energy(own);
      const double at_rest = list[j]->energy(at_rest_state);
      admittances += full;
      e.kinetic += std::max(0.0, full - at_rest);
      e.absolute += std::abs(full) + std::abs(at_rest);
    }
    e.total = network_.add_stored_energy(x, admittances);
    e.stored = std::max(0.0, e.total - admittances);
    e.absolute += e.stored;
    return e;
  }

  struct AdmittanceSlots {
    int offset;
    int size;
    std::vector<int> velocities;  // entries of the admittance's state that are velocities
  };

  Network& network_;
  double tolerance_;
  std::vector<AdmittanceSlots> admittance_slots_;
  Vec scratch_;
  double energy_ = 0.0;
  double moved_ = 0.0;
  double absolute_ = 0.0;
  double work_ = 0.0;
  double floor_ = INFINITY;
  double rise_ = 0.0;
  long observations_ = 0;
  bool defined_ = false;     // some observed energy was finite
  bool overflowed_ = false;  // then one was not
};

}  // namespace stiction::core
