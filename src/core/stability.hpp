// Linear stability of the integrators on a scene. The step map x(k) -> x(k+1) of a stepper
// (with the impedances' stage sizes included, so Kikuuwe friction is priced as it really
// runs) is linearized by central differences at states sampled from a run; a step size is
// stable there when the spectral radius of that Jacobian does not exceed 1. The largest
// stable step is found by bisection. This sees the stiffest element whatever it is (contact
// normal, friction spring, penalty joint) with its real effective mass and damping.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/network.hpp"
#include "core/simulation.hpp"

namespace stiction::core {

struct TimedState {
  double t = 0.0;
  Vec x;
};

// States along a run of the scene (at its own options), `count` of them evenly in time.
std::vector<TimedState> sample_states(Network& network, const RunOptions& options, int count);

// Spectral radius of the linearized step map of `integrator` with step h at (t, x).
double step_spectral_radius(Network& network, const std::string& integrator, double t,
                            const Vec& x, double h);

struct StepLimit {
  double max_step = 0.0;        // largest stable step found (0: none above h_min)
  double limiting_time = 0.0;   // time of the sampled state that limits it
  bool unbounded = false;       // stable up to h_max
};

// Bisection (in log h) between h_min and h_max for the largest h that is stable at every
// sampled state. Fixed-step integrators only.
StepLimit predict_step_limit(Network& network, const std::string& integrator,
                             const std::vector<TimedState>& states, double h_min = 1e-9,
                             double h_max = 1.0);

}  // namespace stiction::core
