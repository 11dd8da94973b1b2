// The paper's network of components (eq. 13, Fig. 2): admittances, impedances with their
// coordinate maps, and one contiguous state vector [x_1 .. x_NA, y_1 .. y_NI]. The network
// evaluates the whole system derivative F(x, t; tau) for the integrators; every loop is
// order-insensitive, and all scratch is allocated once in finalize().
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/admittance.hpp"
#include "core/capabilities.hpp"
#include "core/coordinate_map.hpp"
#include "core/impedance.hpp"
#include "core/islands.hpp"

namespace stiction::core {

struct LayoutEntry {
  std::string component;
  std::string type;
  int offset = 0;
  int size = 0;
  std::vector<std::string> labels;
};

class Network {
 public:
  void add_admittance(std::unique_ptr<Admittance> admittance);
  void add_impedance(std::unique_ptr<Impedance> impedance, std::unique_ptr<CoordinateMap> map);
  // Assigns slices and allocates scratch; call once after the last add.
  void finalize();

  int state_dim() const { return state_dim_; }
  Vec initial_state() const;
  std::vector<LayoutEntry> layout() const;

  // x_dot = F(x, t; tau): (13b)-(13g) with (22).
  void derivative(double t, ConstVecRef x, double tau, VecRef x_dot) {
    derivative_at(t, x.data(), tau, x_dot.data());
  }
  // The same on plain pointers to whole state vectors (state_dim() values each), for the
  // steppers' hot loops: a ConstVecRef made from a Vec is an object on the caller's stack
  // with a destructor to run, at every stage.
  void derivative_at(double t, const double* x, double tau, double* x_dot);
  // The part of F(x, t; tau) that an island's impedances and admittances make
  // (core/islands.hpp): its state rates in x_dot, computed as derivative_at() does, and
  // nothing else written. A pending slip capture stays pending.
  void derivative_part(double t, const double* x, double tau, double* x_dot, const Island& part);
  // F(x, t; tau) with the friction of every ClampedFriction element held at what it is at
  // `reference`: for stability analysis only.
  // With `part`, of that island only (its entries of x_dot; the rest is not written).
  void derivative_friction_held(double t, ConstVecRef x, double tau, VecRef x_dot,
                                const Vec& reference, const Island* part = nullptr);
  // Most energy the friction-clamping elements' bounded oscillations can hold at x (with
  // `part`, those of that island).
  double friction_cap_energy(ConstVecRef x, const Island* part = nullptr);
  // Normalizes the quaternions (of the island's bodies only, with `part`).
  void project(VecRef x, const Island* part = nullptr) const;
  // Each admittance's Admittance::solve_kinematics on its slices of start and iterate.
  void solve_kinematics(const Vec& start, Vec& iterate, double h,
                        const Island* part = nullptr) const;
  // Admittance derivatives with no forces applied: the position rates (p_dot = v,
  // q_dot = Q(w, q), theta_dot = omega) of a state, for partitioned integrators (with
  // `part`, the island's entries only).
  void kinematics(ConstVecRef x, VecRef x_dot, const Island* part = nullptr) const;
  // True for the admittance slots that are positions (not velocities); impedance states
  // are false.
  const std::vector<bool>& position_slots() const { return position_slots_; }

  std::vector<std::string> signal_columns() const;
  int signal_count() const { return signal_count_; }
  // For each signal column: whether it is an angle reported modulo 2 pi.
  std::vector<bool> wrapped_columns() const;
  // Evaluates the network at (t, x; tau) and writes one value per signal column.
  void write_signals(double t, ConstVecRef x, double tau, VecRef row);

  // Slip velocity of impedance i (which must be a SlipElement) at state x.
  Vec3 slip_velocity(int impedance, ConstVecRef x);
  // Impedance i's input x_hat at state x (the map's Psi), valid until the next call.
  ConstVecRef impedance_input(int impedance, ConstVecRef x);

  // Slip inputs from the step's own evaluation (issue 13): after capture_slip_inputs_next(),
  // the next derivative() call also keeps every slip element's x_hat and state as it
  // evaluated them, so the run loop observes slips without evaluating the maps again. Without
  // a request derivative() runs the plain couplings (no copy, no test); the request swaps in
  // the capturing twins (Coupling::capturing) for that one call.
  void capture_slip_inputs_next() { active_ = capturing_.data(); }
  // True between a request and the derivative() call that serves it.
  bool capture_pending() const { return active_ != plain_.data(); }
  void cancel_capture() { active_ = plain_.data(); }
  // Impedance i's x_hat and state (i must be a slip element) at the last captured evaluation.
  ConstVecRef captured_input(int impedance) const;
  ConstVecRef captured_state(int impedance) const;

  // Regimes of all impedances at (x; tau) folded into one number: equal numbers mean the
  // same smooth piece of the system (see PiecewiseLaw). With `part`, of its impedances.
  std::size_t regime_signature(ConstVecRef x, double tau, const Island* part = nullptr);

  // Power fed in by source elements at (t, x); with driven_only, by those whose output is
  // a function of time alone (not Source::reads_state()).
  double source_power(double t, ConstVecRef x, bool driven_only = false);
  bool has_sources() const;
  bool has_feedback_sources() const;

  // Energy of the admittances plus what the impedances' springs hold (NaN if an
  // admittance does not define its energy).
  double energy(ConstVecRef x);
  // The impedances' stored energies at x added one by one to `total`, in the order energy()
  // adds them to the admittances' sum (so that a caller summing the admittances itself, as
  // the run's energy monitor does, gets energy(x) to the bit).
  double add_stored_energy(ConstVecRef x, double total);

  const Admittance* find_admittance(const std::string& name) const;
  const std::vector<std::unique_ptr<Admittance>>& admittances() const { return admittances_; }
  const std::vector<std::unique_ptr<Impedance>>& impedances() const { return impedances_; }
  const CoordinateMap& map_of(int impedance) const { return *maps_[impedance]; }
  // Impedance i's capabilities (core/capabilities.hpp), resolved once by finalize().
  const Capabilities& capabilities(int impedance) const { return capabilities_[impedance]; }
  Slot admittance_slot(int admittance) const { return admittance_slots_[admittance]; }
  // Impedance i's state slice (state_offset, state_size) and where its x_hat starts in the
  // network's motion vector (input_offset, input_size).
  Slot impedance_slot(int impedance) const { return impedance_slots_[impedance]; }
  int input_dim() const { return static_cast<int>(u_hat_.size()); }  // size of all u_hat

 private:
  // Psi, impedances, Phi through the maps' and impedances' interfaces, leaving every
  // impedance's x_hat and u in x_hat_ and u_ (for signals); derivative() goes through the
  // couplings instead, which compute the same. With a friction reference, clamping friction
  // is held at its value there (derivative_friction_held).
  // With `part`, the island's impedances only, into its admittances' inputs.
  void evaluate_impedances(double t, ConstVecRef x, double tau, VecRef x_dot,
                           const Vec* friction_reference = nullptr, const Island* part = nullptr);
  // Calls f(i) for every index in `listed` (an island's impedances or admittances), or
  // for 0 .. count - 1 without a list.
  template <typename F>
  static void for_each_index(const std::vector<int>* listed, std::size_t count, F f);
  [[gnu::always_inline]] inline void evaluate_admittances(const double* x, double* x_dot);

  std::vector<std::unique_ptr<Admittance>> admittances_;
  std::vector<std::unique_ptr<Impedance>> impedances_;
  std::vector<std::unique_ptr<CoordinateMap>> maps_;
  std::vector<std::unique_ptr<Coupling>> couplings_;  // one per impedance, built by finalize()
  std::vector<Capabilities> capabilities_;            // one per impedance, found by finalize()
  std::vector<int> sources_;                          // the impedances that are Sources
  std::vector<Slot> admittance_slots_;
  // What derivative_at() walks, flat: each admittance with its state and input offsets, and
  // the counts held as plain ints (a vector's size is read back from memory after every
  // virtual call, which may have changed it as far as the compiler knows).
  struct AdmittanceCall {
    const Admittance* admittance;
    int state_offset;
    int input_offset;
  };
  std::vector<AdmittanceCall> admittance_calls_;
  int coupling_count_ = 0;
  int admittance_count_ = 0;
  int input_count_ = 0;
  std::vector<Slot> impedance_slots_;  // state slice; input_offset/size index x_hat, u
  std::vector<int> output_offsets_;    // where each impedance's u lives in u_
  std::vector<int> output_sizes_;
  std::vector<int> admittance_signal_sizes_;
  std::vector<int> impedance_signal_sizes_;
  int state_dim_ = 0;
  int signal_count_ = 0;
  bool finalized_ = false;
  Vec x_hat_;  // all impedance inputs
  Vec u_;      // all impedance outputs
  Vec u_hat_;  // all admittance inputs
  Vec scratch_dot_;
  Vec zero_input_;
  std::vector<bool> position_slots_;
  // Slip capture (capture_slip_inputs_next): the couplings derivative() runs, plain or with
  // the capturing twins of the slip elements, and where each slip element's x_hat and state go.
  void prepare_capture();
  std::vector<Coupling*> plain_;
  std::vector<Coupling*> capturing_;
  std::vector<std::unique_ptr<Coupling>> capturing_owned_;
  Coupling* const* active_ = nullptr;  // plain_ or capturing_ (their buffers survive a move)
  std::vector<int> capture_offsets_;   // -1: no slip
  Vec captured_;
};

}  // namespace stiction::core
