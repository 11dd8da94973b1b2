// Linear stability of the integrators on a scene. At states sampled from a run, the system
// derivative F(x; tau) is linearized by central differences, once for each stage size the
// method passes (so Kikuuwe friction is priced as it really runs), and the method's linear
// step map is built from those Jacobians: for a Runge-Kutta tableau
//   K_r = J(tau_r) (I + h sum_j a_rj K_j),   Phi = I + h sum_r b_r K_r,
// with the regime of every element frozen at the state (the standard analysis; a contact
// that closes for less than a step is still analysed as closed). A step size is stable at
// a state when the spectral radius of Phi does not exceed 1 (plus a small allowance).
//
// Friction that clamps its force at a limit (the ClampedFriction capability) is linearized a
// second time with its force held. A mode that only the first linearization shows lives
// in a stuck friction spring: it cannot run away, since it ends where the force reaches the
// limit and the element slides. It holds at most friction_cap_energy(), so the run's energy
// monitor sees it only where that exceeds the monitor's headroom at that state; there it
// counts as an instability, elsewhere it is reported as friction chatter.
#pragma once

#include <atomic>
#include <string>
#include <vector>

#include "core/network.hpp"
#include "core/simulation.hpp"

namespace stiction::core {

struct TimedState {
  double t = 0.0;
  Vec x;
  // How much more the network energy may grow at t before the run's energy monitor calls
  // the run unstable.
  double energy_headroom = 0.0;
};

// States along a run of the scene at its own options: up to `per_regime` of the steps of
// each smooth piece (regime signature) the run passes through, evenly spread over them, so
// brief regimes (a contact closed for a few steps) are sampled as surely as long ones; at
// most kMaxSampledStates in all (each regime's first ones first), so that the analysis
// stays within seconds whatever the scene.
inline constexpr std::size_t kMaxSampledStates = 48;
std::vector<TimedState> sample_states(Network& network, const RunOptions& options, int per_regime);

// A step is called unstable where it amplifies some mode by more than this per step: such
// growth runs away within tens of steps. Weaker growth is left out on purpose: a rolling
// contact linearized about a point of its orbit grows at a few 1/s (physics, not the step).
inline constexpr double kUnstableGrowth = 0.05;

struct StepRadius {
  double full = 0.0;           // spectral radius of the linear step map
  double friction_held = 0.0;  // same, with clamping friction held
  double friction_cap = 0.0;   // Network::friction_cap_energy at the state
  bool smooth = false;         // false: the state lies on a switching surface; no answer
};

// Spectral radii of the linearized step map of `integrator` with step h at (t, x), island by
// island (core/islands.hpp: no element couples two islands, so the step map is block
// diagonal over them), folded into one answer (the largest radii). Fixed-step integrators
// only (euler, symplectic_euler, heun, rk4, implicit). Islands of more than
// kMaxAnalysedStates states, and islands on a switching surface, give no answer; smooth is
// false only where no island gives one.
StepRadius step_radius(Network& network, const std::string& integrator, double t, const Vec& x,
                       double h);

// Whether radii r make the step unstable at a state where the energy monitor has `headroom`
// left: a mode grows faster than kUnstableGrowth and either runs away with the friction
// held, or is a stuck friction's chatter holding more energy than the monitor allows (with
// chatter_counts: any such mode). False on a switching surface (no answer there).
bool unstable_step(const StepRadius& r, double headroom, bool chatter_counts = false);

// The linearization is dense per island: every sampled state and every step size tried
// costs a few Jacobians of n columns (n evaluations of the island each) and an n x n
// eigenvalue problem, so an island's analysis grows as n^3 and a 1000-link arm (3000 states
// in one island) would take hours (issue 25). A network with an island above this many
// states is not analysed, and says so (StepLimit::skipped): at 240 states one radius costs
// tens of milliseconds here, so the whole analysis stays within seconds and a signal is
// answered between two radii. Separate bodies are separate islands: 1000 spheres on a floor
// are 1000 islands of 13 states. The single-element figures `check` prints (each stiff
// element against its effective mass) cost one derivative per element and remain.
inline constexpr int kMaxAnalysedStates = 240;
// States in the network's largest island.
int largest_island_states(const Network& network);
inline bool analysable(const Network& network) {
  return largest_island_states(network) <= kMaxAnalysedStates;
}

// Work the step analysis may spend, in units of one radius (the cube of the size of each
// irreducible block of the island's sparsity pattern, core/spectrum.hpp, plus n^2 for its
// Jacobian, summed), shared by the searches it is passed to. Machine-independent, so that
// `check` gives the same answer on any machine.
struct AnalysisBudget {
  double limit = 0.0;
  double spent = 0.0;
};

struct StepLimit {
  bool skipped = false;        // too many states for the dense analysis (kMaxAnalysedStates)
  bool interrupted = false;    // `stop` was set, or the budget ran out, before the search ended
  bool over_budget = false;    // the budget ran out: no answer
  double max_step = 0.0;       // largest stable step found (0: none above h_min)
  double limiting_time = 0.0;  // time of the sampled state that limits it
  bool unbounded = false;      // stable up to h_max
  // Same, with modes of stuck friction counted everywhere (<= max_step: from here up to
  // max_step stuck friction chatters, bounded by its limit force).
  double chatter_free_step = 0.0;
};

// The largest h in [h_min, h_max] below which every step is stable at every sampled state:
// the first unstable step on a grid of ratio 10^0.1, then bisection in log h to 0.1%.
// Fixed-step integrators only. `stop` (SIGINT/SIGTERM) is polled before every radius, so the
// search ends within a fraction of a second of it (StepLimit::interrupted). A network of more
// than kMaxAnalysedStates states is not analysed (StepLimit::skipped).
StepLimit predict_step_limit(Network& network, const std::string& integrator,
                             const std::vector<TimedState>& states, double h_min = 1e-9,
                             double h_max = 1.0, const std::atomic<bool>* stop = nullptr,
                             AnalysisBudget* budget = nullptr);

}  // namespace stiction::core
