// The energy monitor's view of feedback sources (issue 10). The run's monitor
// (instability_monitor.cpp) allows the network energy to grow by the work the sources put in
// (and a tolerance of the scene's energy scale: core/energy_budget.hpp). That is
// right for a source driven by time, but a feedback law (a torque that reads the state, as a
// PD controller: Source::reads_state) is a spring and a damper in disguise: in a numerically
// unstable closed loop its power swings with the runaway mode, and crediting the work it
// does "pays" for the growth the integrator makes, so such a run was never flagged (pd_arm at
// 4x its step limit reached 3e7 rad in 2 s with exit 0). The test errs the other way too:
// sampled every 8 steps, the power of a controller lifting an arm at a large but stable step
// misses most of its work, and the lift was called unstable.
//
// Its work cannot simply be dropped either (a controller lifting an arm raises its energy
// for real), and it cannot be split into what is stored and what is put in without knowing
// the law. So with feedback sources the energy only says when to look, and the step map
// says what is wrong: where the energy has grown past what the time-driven sources alone
// allow (the budget with only their work credited), the step map is linearized (core/stability.hpp,
// the same analysis as `stiction check`), and the run is unstable if a mode grows faster than
// kUnstableGrowth per step. A stable closed loop (the scene's step, or a step below the predicted
// limit) passes that test wherever its energy is; the linearization is done again only each time
// the excess has doubled, so a stable run does it a few tens of times, while a runaway is caught at
// the first check where its energy shows.
//
// Where the linearization has no answer at the checked state (a switching surface, or a
// runaway already at 1e9 rad, where differences relative to the state cannot resolve
// gravity's cos(theta)), the steps since the previous check are taken again from the state
// kept there, and the first replayed state with an answer decides.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "core/energy_budget.hpp"
#include "core/integrator.hpp"
#include "core/network.hpp"
#include "core/simulation.hpp"
#include "core/stability.hpp"

namespace stiction::core {

class FeedbackMonitor {
 public:
  // Active with feedback sources, a network energy and a fixed-step integrator
  // (rk4_adaptive's error control keeps its own steps stable).
  FeedbackMonitor(Network& network, const RunOptions& options, const Vec& x0);
  bool active() const { return active_; }
  // At a check of the run's monitor at (t, x), x_prev the state a step before, with the
  // run's budget (the work of all sources credited) updated to x: why the run is unstable,
  // if it is.
  std::optional<std::string> check(double t, const Vec& x_prev, const Vec& x,
                                   const EnergyBudget& all_sources);

 private:
  // The step map's radii at x, else at x_prev, else at the replayed steps since the last
  // check; smooth == false if none has an answer.
  StepRadius radius(double t, const Vec& x_prev, const Vec& x);

  Network& network_;
  const RunOptions& options_;
  bool active_;
  EnergyBudget driven_;       // with only the time-driven sources' work credited
  double driven_work_ = 0.0;  // |work| of the time-driven sources so far
  double power_checked_ = 0.0;
  double t_checked_ = 0.0;
  Vec x_checked_;                 // the state at the last check
  double verified_excess_ = 0.0;  // excess at the last linearization that found the step stable
  std::unique_ptr<Stepper> replay_;
};

}  // namespace stiction::core
