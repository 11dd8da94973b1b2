// `--integrator implicit`: backward Euler over the whole network, for stiff elements (the
// paper's contacts at K = 1e7 N/m) at steps far above the explicit methods' limits.
//
// One step of h solves  x(k+1) = x(k) + h F(t + h, x*; tau = h)  by Newton's method, where
// x* is x(k+1) except in the states of clamped friction (Kikuuwe's elements, the
// ClampedFriction capability), which keep their value at x(k). That is no approximation:
// Kikuuwe's law (paper eq. 19) with tau = h *is* the backward Euler step of its own spring,
// solved in closed form given the motion at the step's end:
//   f = gsat(F, (B + h K) v(k+1) + K e(k)),  e(k+1) = e(k) + h eps,
// so every Kikuuwe element is passed the step it needs, and a stuck one gets
// e(k+1) - e(k) = h v(k+1), the same increment as the position it holds: its anchor does not
// drift, as under the paper's RK4. The other elements' states (LuGre, Dahl) are solved
// implicitly with the bodies.
//
// Newton: the first evaluation is at x(k) itself (the run loop reads the state's slips from
// it), each later one at the current iterate. The iteration matrix I - h dF/dx* is built
// from forward differences over the solved entries only (a contact's friction state is not
// one), block diagonal over the groups of entries that no element couples (the network's
// coupling graph: separate bodies; one evaluation perturbs an entry of every group),
// LU-factored block by block, and reused across iterations and steps until the iteration
// contracts too slowly (a change of regime: an element sticks, slides, touches or lifts off;
// at most kMaxMatricesPerStep times a step) or the step size changes. A correction that
// grows is halved (damped Newton). Once the correction is below the tolerance the state is
// set to x(k) + h F at the last iterate, so positions and friction states move by the same
// velocities. A step whose iteration does not converge is split in two (at most
// kMaxSplits deep), then reported as an instability.
#pragma once

#include <Eigen/LU>
#include <string>
#include <vector>

#include "core/integrator.hpp"

namespace stiction::core {

// The state entries an implicit step solves for: all but the states of clamped friction
// (their law solves them in closed form). True = solved.
std::vector<bool> implicitly_solved_slots(const Network& network);

class ImplicitEulerStepper final : public Stepper {
 public:
  ImplicitEulerStepper(int state_dim, double dt);
  const std::string& name() const override { return name_; }
  int order() const override { return 1; }
  double advance(Network& network, double t, double limit, Vec& x) override;
  bool evaluates_start_first() const override { return true; }
  // Blocks of the iteration matrix (groups of unknowns no element couples); 0 before the
  // first step.
  std::size_t blocks() const { return groups_.size(); }

  // One backward Euler stage, for the implicit Runge-Kutta methods built on this one
  // (each SDIRK stage is a backward Euler step of gamma h from its own start): solves
  // x(end) = x + h F(t + h, x*(end); tau = h) from (t, x) into x, without splitting;
  // false if Newton did not converge (x unchanged then). The network is first evaluated at
  // (t + h, x) itself.
  bool solve_stage(Network& network, double t, double h, Vec& x) {
    if (!prepared_) prepare(network);
    return solve(network, t, h, x);
  }
  // F at the solution of the last stage that converged (x(end) = x + h slope()).
  const Vec& slope() const { return f_; }
  // With keep_start_slope(true), each solve also keeps its first evaluation, F(t + h, x;
  // tau = h) at the stage's start x (a variable-step method's dense output reads it).
  void keep_start_slope(bool keep) { keep_start_slope_ = keep; }
  const Vec& start_slope() const { return f_start_; }
  // Applies the inverse of the current iteration matrix, I - h dF/dx* over the solved
  // entries (h: the last stage's), to those entries of v, leaving the others: the filter of
  // an embedded error estimate that keeps it bounded on stiff modes (Hairer & Wanner,
  // Solving ODEs II, section IV.8). False (v unchanged) if there is no matrix yet.
  bool apply_inverse(Vec& v);

 private:
  static constexpr int kMaxIterations = 16;
  static constexpr int kMaxSplits = 6;
  static constexpr int kMaxBandMoves = 2;        // per step
  static constexpr int kMaxHalvings = 4;         // per step: damped Newton where it grows
  static constexpr int kMaxMatricesPerStep = 4;  // formed anew where the iteration stalls
  // Tolerance of a Newton correction's entry i: kRelative |x_i| + kAbsolute.
  static constexpr double kRelative = 1e-12;
  static constexpr double kAbsolute = 1e-13;
  // Corrections that stall below this many tolerances are taken as converged (rounding).
  static constexpr double kRoundingFloor = 100.0;

  void prepare(Network& network);
  // One backward Euler step of h from (t, x) into x; false if Newton did not converge
  // (x unchanged then).
  bool solve(Network& network, double t, double h, Vec& x);
  // Steps of h / 2^depth until h is covered; false if one still fails at kMaxSplits.
  bool split(Network& network, double t, double h, Vec& x, int depth);
  // F at the merged iterate into f_, and the residual of the solved entries.
  void evaluate_iterate(Network& network, double t_end, double h);
  // Moves the iterate back along the last Newton step to where a sliding clamped-friction
  // element whose slip that step reversed reaches the middle of its stuck band
  // (ClampedFriction::unloaded_slip); false if no element reversed.
  bool move_into_stuck_band(Network& network, double h);
  // x* from the solved entries of `iterate` and the rest of `start`.
  void merge(const Vec& iterate, const Vec& start);
  // The unknowns (positions in `solved`) in groups that no element couples.
  static std::vector<std::vector<int>> coupled_groups(const Network& network,
                                                      const std::vector<int>& solved);
  // delta_ = the matrix's inverse applied to residual_, block by block.
  void solve_linear();
  // Forms I - h dF/dx* over the solved entries at x* (eval_), with F there in f_, and
  // factors it.
  void refresh_matrix(Network& network, double t_eval, double h);
  // The largest entry of a Newton correction relative to its tolerance at state x.
  double scaled_norm(const Vec& correction, const Vec& x) const;

  std::string name_ = "implicit";
  double dt_;
  bool prepared_ = false;
  std::vector<int> solved_;             // indices of the solved entries
  std::vector<int> friction_elements_;  // impedances with clamped friction and a slip
  Vec start_, iterate_, eval_, f_, probe_, f_probe_, last_eval_, residual_, delta_;
  // The iteration matrix is block diagonal over groups of unknowns that no element couples
  // (separate bodies): one dense block and LU per group, positions into solved_.
  std::vector<std::vector<int>> groups_;
  std::vector<Eigen::MatrixXd> blocks_;
  std::vector<Eigen::PartialPivLU<Eigen::MatrixXd>> block_lus_;
  std::vector<Vec> block_rhs_;  // scratch per block
  Vec probe_delta_;
  bool lu_valid_ = false;
  double lu_h_ = 0.0;
  bool keep_start_slope_ = false;
  Vec f_start_;
};

}  // namespace stiction::core
