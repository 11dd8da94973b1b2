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
// Newton runs per island (core/islands.hpp: the bodies no element couples, with their
// elements): each island iterates, forms and factors its own matrix, halves and splits its
// own step, so a sphere switching from slip to roll costs the other 999 nothing, and the
// step costs O(N) in the number of separate bodies. A contact between two bodies that the
// step cannot close (NormalContact::gap > 2 h approach_speed at the step's start) is
// detached: the two bodies step as separate islands. If one closes after all, the step is
// taken again with it attached. The step starts with one evaluation of
// the whole network at x(k) (the run loop reads the state's slips from it; it is every
// island's first residual); each later one is of the island's part only
// (Network::derivative_part), counted in evaluations() by its share of the state.
//
// An island's iteration matrix I - h dF/dx* is built from forward differences over its
// solved entries (a contact's friction state is not one), compressed by the island's
// coupling graph (core/jacobian_pattern.hpp: bodies that share no element's reach are
// perturbed in one evaluation), LU-factored (sparse for large, sparse islands), and reused across
// iterations and steps until its iteration contracts too slowly (a change of regime: an
// element sticks, slides, touches or lifts off; at most kMaxMatricesPerStep times a step)
// or the step size changes. A correction that grows is halved (damped Newton). Once the
// correction is below the tolerance the island's state is set to x(k) + h F at the last
// iterate, so positions and friction states move by the same velocities. An island whose
// iteration does not converge is stepped in halves (at most kMaxSplits deep, the other
// islands keep their full step), then reported as an instability naming its first body.
#pragma once

#include <Eigen/LU>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <memory>
#include <string>
#include <vector>

#include "core/integrator.hpp"
#include "core/islands.hpp"
#include "core/jacobian_pattern.hpp"

namespace stiction::core {

// An island named for a user in a message: " in the island of 'its first body'" (or its
// first element where it has no body).
std::string in_island_of(const Network& network, const Island& part);

// The state entries an implicit step solves for: all but the states of clamped friction
// (their law solves them in closed form). True = solved.
std::vector<bool> implicitly_solved_slots(const Network& network);

// The inverse of a square matrix of up to kSmallInverseUnknowns rows, bit for bit what
// Eigen::PartialPivLU<MatrixXd>(matrix).inverse() gives (Eigen 3.4: its unblocked LU with
// partial pivoting, the row swaps applied to the identity, then its triangular solves, which
// update the rows past each panel of four columns by the panel's sum), without the blocked
// kernels' packing, heap buffers and dispatch: on a body's 13 unknowns they cost three times
// the arithmetic. Bit for bit under the build's flags (SSE2, no FMA contraction); with FMA
// the same inverse to rounding. lu: scratch, n x n afterwards.
inline constexpr int kSmallInverseUnknowns = 16;
void small_inverse(const Eigen::MatrixXd& matrix, Eigen::MatrixXd& lu, Eigen::MatrixXd& inverse);

class ImplicitEulerStepper final : public Stepper {
 public:
  ImplicitEulerStepper(int state_dim, double dt);
  const std::string& name() const override { return name_; }
  int order() const override { return 1; }
  double advance(Network& network, double t, double limit, Vec& x) override;
  bool evaluates_start_first() const override { return true; }
  // Islands (each with its own matrix); 0 before the first step.
  std::size_t blocks() const { return islands_.size(); }
  // Whether contacts between bodies that are apart detach (true, the default); false keeps
  // the islands structural (for comparison). Call before the first step.
  void set_detach_contacts(bool on) { detach_contacts_ = on; }
  // Whether an island's matrix is formed by compressed differences (true, the default) or
  // one column per evaluation (for comparison: both give the same matrix). Call before the
  // first step.
  void set_compressed_differences(bool on) { compress_ = on; }
  // Whether a compressed group of a large island may be evaluated on its star, the elements
  // its columns change (true, the default; core/jacobian_pattern.hpp); false evaluates the
  // whole island for every group (for comparison: the same matrix but for rounding in the
  // rows of the bodies beside the perturbed ones). Call before the first step.
  void set_star_columns(bool on) { stars_ = on; }
  // Islands of at least this many unknowns whose pattern is sparse are factored by a sparse
  // LU (default kSparseUnknowns). Call before the first step.
  void set_sparse_unknowns(Eigen::Index n) { sparse_unknowns_ = n; }
  // Iteration matrices formed so far, over all islands.
  long matrices_formed() const { return matrices_formed_; }
  // Evaluations spent forming them, in island evaluations (not whole-network units).
  long matrix_evaluations() const { return matrix_evaluations_; }
  // Islands now factored by the sparse LU.
  int sparse_islands() const;

  // One backward Euler stage, for the implicit Runge-Kutta methods built on this one
  // (each SDIRK stage is a backward Euler step of gamma h from its own start): solves
  // x(end) = x + h F(t + h, x*(end); tau = h) from (t, x) into x, without splitting;
  // false if Newton did not converge in some island (x unchanged then). The network is
  // first evaluated at (t + h, x) itself.
  bool solve_stage(Network& network, double t, double h, Vec& x);
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

  // Step groups: parts of the network that no element can couple (core/islands.hpp's
  // islands of the network's structure, each contact between bodies included), which an
  // integrator may advance on steps of their own (core/island_sdirk.hpp). A group's Newton
  // islands are the islands within it; its stage is solved from its own entries alone.
  // Call before the first step; the groups must cover the islands of the network.
  void set_step_groups(const std::vector<Island>& groups);
  // solve_stage and apply_inverse for group g's entries only (the others untouched, and
  // not read: they may be at other times). slope() and start_slope() are set on its entries.
  bool solve_stage(Network& network, double t, double h, Vec& x, int group);
  bool apply_inverse(Vec& v, int group);

 private:
  static constexpr int kMaxIterations = 16;
  static constexpr int kMaxSplits = 6;
  static constexpr int kMaxBandMoves = 2;        // per step
  static constexpr int kMaxHalvings = 4;         // per step: damped Newton where it grows
  static constexpr int kMaxMatricesPerStep = 4;  // formed anew where the iteration stalls
  // Steps within this relative difference share an iteration matrix (rounding of h).
  static constexpr double kSameStep = 1e-9;
  // Islands of up to this many unknowns keep their matrix's inverse (correct()).
  static constexpr Eigen::Index kInverseUnknowns = 24;
  // Islands from this many unknowns, with at most kSparseFill of their matrix in the
  // pattern, use the sparse LU: a tower of 100 boxes (1300 unknowns, 2% filled) factors in
  // a fraction of the dense LU's 0.7 GFlop.
  static constexpr Eigen::Index kSparseUnknowns = 128;
  static constexpr double kSparseFill = 0.2;
  // Tolerance of a Newton correction's entry i: kRelative |x_i| + kAbsolute.
  static constexpr double kRelative = 1e-12;
  static constexpr double kAbsolute = 1e-13;
  // Corrections that stall below this many tolerances are taken as converged (rounding).
  static constexpr double kRoundingFloor = 100.0;

  // A stretch of consecutive state entries, entry .. entry + length - 1, that an island's
  // list holds at positions index .. index + length - 1. An island's entries come in few
  // stretches (a body's slice, an element's), so the step's copies and updates run as
  // vector operations per stretch rather than one indexed entry at a time: the same
  // arithmetic on each entry, the same bits, in a fraction of a small island's step.
  struct Run {
    int entry = 0;
    int index = 0;
    int length = 0;
  };
  static std::vector<Run> runs_of(const std::vector<int>& entries);

  // One island's Newton solver: what it solves, its matrix and its scratch.
  struct IslandSolve {
    Island island;                       // its part of the network
    std::vector<int> solved;             // the state entries Newton solves for
    std::vector<Run> state_runs;         // island.states in stretches
    std::vector<Run> solved_runs;        // solved in stretches (index: into solved)
    std::vector<int> friction_elements;  // clamped friction with a slip
    double share = 0.0;                  // states / state_dim: its evaluation's cost
    JacobianPattern pattern;  // which columns share an evaluation, which rows they change
    Eigen::MatrixXd matrix;
    Eigen::PartialPivLU<Eigen::MatrixXd> lu;
    // Sparse islands: the matrix in the pattern's structure and its LU (analysed once).
    bool sparse = false;
    bool sparse_factored = false;  // false: the sparse LU failed, the dense one holds
    Eigen::SparseMatrix<double> sparse_matrix;
    std::unique_ptr<Eigen::SparseLU<Eigen::SparseMatrix<double>>> sparse_lu;
    Eigen::MatrixXd inverse;   // of small islands only (kInverseUnknowns)
    Eigen::MatrixXd small_lu;  // small_inverse's scratch
    Vec residual, delta, probe_delta;
    // Per solved entry: the tolerance of a correction at this step's start (scaled_norm).
    Vec scale;
    bool lu_valid = false;
    double lu_h = 0.0;
  };

  // A step group (set_step_groups): its part of the network, its entries in stretches, its
  // Newton islands (indices into islands_, kept by build_islands) and contacts between its
  // bodies.
  struct StepGroup {
    Island part;
    std::vector<Run> runs;
    std::vector<int> islands;
    std::vector<int> separable;
    double share = 0.0;
  };

  void prepare(Network& network);
  static void copy_runs(const std::vector<Run>& runs, const Vec& from, Vec& to);
  // The island's pattern (compressed or one column per evaluation) and, for a large sparse
  // island, its sparse matrix's structure.
  void set_pattern(Network& network, IslandSolve& s) const;
  // delta = the iteration matrix's inverse applied to the residual.
  void correct(IslandSolve& s);
  // apply_inverse over the listed islands (nullptr: all).
  bool apply_inverse_over(Vec& v, const std::vector<int>* listed);
  // (Re)builds islands_ for the current detached_ set, keeping the matrices of the islands
  // that are unchanged.
  void build_islands(Network& network);
  // Detaches the contacts between bodies that a step of h from x cannot close, attaches the
  // others; rebuilds the islands if that changed anything.
  // contacts: those to look at (nullptr: every separable one).
  void update_detached(Network& network, const Vec& x, double h,
                       const std::vector<int>* contacts = nullptr);
  // Attaches the detached contacts that are closed at x; true if there were any (the step
  // that led to x is then taken again).
  bool attach_closed(Network& network, const Vec& x, const std::vector<int>* contacts = nullptr);
  // Every island from (t, x) by h: with splits (a step) or without (a stage); false if an
  // island failed (the failing one in failed_).
  bool solve_islands(Network& network, double t, double h, Vec& x, bool may_split);
  // One backward Euler step of h from (t, x) for island `s`'s entries of x; false if Newton
  // did not converge (x unchanged then). With start_known, f_ already holds F at
  // (t + h, x) on the island's entries.
  bool solve(Network& network, IslandSolve& s, double t, double h, Vec& x, bool start_known);
  // Island steps of h / 2^depth until h is covered; false if one still fails at kMaxSplits.
  bool split(Network& network, IslandSolve& s, double t, double h, Vec& x, int depth);
  // The island's part of F at (t, y) into out.
  void evaluate_part(Network& network, IslandSolve& s, double t, const Vec& y, double h, Vec& out);
  // The star's part of F at (t, y) into out, counted by its share of the state.
  void evaluate_star(Network& network, const Island& star, double t, const Vec& y, double h,
                     Vec& out);
  // F at the merged iterate into f_, and the island's residual.
  void evaluate_iterate(Network& network, IslandSolve& s, double t_end, double h);
  // Moves the iterate back along the last Newton step to where a sliding clamped-friction
  // element whose slip that step reversed reaches the middle of its stuck band
  // (ClampedFriction::unloaded_slip); false if no element reversed.
  bool move_into_stuck_band(Network& network, IslandSolve& s, double h);
  // Forms I - h dF/dx* over the island's solved entries at x* (eval_), with F there in f_,
  // and factors it.
  void refresh_matrix(Network& network, IslandSolve& s, double t_eval, double h);
  // Sets the island's tolerances (scale) at the step's start x.
  static void set_scale(IslandSolve& s, const Vec& x);
  // The largest entry of a Newton correction relative to its tolerance (scale).
  static double scaled_norm(const IslandSolve& s, const Vec& correction);
  // to = from on the island's state entries.
  static void copy_states(const IslandSolve& s, const Vec& from, Vec& to);
  // The island named for a user: its first body.
  std::string describe(const Network& network, const IslandSolve& s) const;
  void count_part_evaluation(const IslandSolve& s);

  std::string name_ = "implicit";
  double dt_;
  bool prepared_ = false;
  std::vector<IslandSolve> islands_;
  bool detach_contacts_ = true;
  std::vector<int> separable_;  // contacts between bodies that can say their gap
  std::vector<char> detached_;  // per impedance: stepped apart from its bodies now
  const IslandSolve* failed_ = nullptr;
  Vec step_start_;
  // Whole-state vectors; each island reads and writes only its own entries.
  Vec start_, iterate_, eval_, f_, probe_, f_probe_, f_star_, last_eval_, stage_;
  double part_evaluations_ = 0.0;  // island evaluations, in whole-network units
  long whole_evaluations_ = 0;
  long matrices_formed_ = 0;
  long matrix_evaluations_ = 0;
  bool compress_ = true;
  bool stars_ = true;
  Eigen::Index sparse_unknowns_ = kSparseUnknowns;
  std::vector<double> column_steps_;
  bool keep_start_slope_ = false;
  Vec f_start_;
  std::vector<StepGroup> groups_;
  std::vector<int> group_of_state_;  // per state entry (-1: in no group)
};

}  // namespace stiction::core
