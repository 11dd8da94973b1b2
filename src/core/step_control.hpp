// The step-size control shared by the adaptive integrators (rk4_adaptive, sdirk2, sdirk4):
// one controller, one rule for accepting a step, one scale for measuring a local error.
//
//   (scaled error of a trial step, the estimate's order q) => (accept?, next step factor)
//
// An error estimate of a step of h that behaves as C h^q is held at 1 (it is scaled by the
// tolerance, scaled_error): a step is accepted when its scaled error is <= 1, and the next
// trial is h * clamp(safety * error^(-1/q), min_factor, max_factor) (Hairer, Norsett and
// Wanner, Solving ODEs I, section II.4). q is the integrator's traits' error_order: 5 for
// rk4_adaptive's step doubling (the local error of a fourth-order step), p_hat + 1 for an
// embedded pair whose lower solution has order p_hat (sdirk2: 2, sdirk4: 4).
#pragma once

#include <cstddef>
#include <functional>

#include "core/network.hpp"

namespace stiction::core {

struct StepController {
  int error_order = 5;       // q: the estimate is O(h^q)
  double safety = 0.9;       // aims a little below the tolerance
  double min_factor = 0.2;   // the most a rejected step shrinks at once
  double max_factor = 4.0;   // the most a step grows at once
  static bool accept(double error) { return error <= 1.0; }
  // The factor the next trial step is multiplied by after a step of scaled error `error`.
  double factor(double error) const;
};

// Per state entry, the size below which its error counts as absolute: 1 (mixed
// absolute/relative), except the spring state e of clamping friction, whose natural size is
// F / K (~3e-7 m for the sphere): against 1 its error would never count, and a large step
// that swings e from +F/K to -F/K (through a stick and out again) would pass.
void set_error_floors(Network& network, const Vec& x, Vec& floor);

// max_i |difference_i| / (divisor tolerance (floor_i + |x_i|)): an error estimate
// (difference / divisor) against the tolerance, in the largest entry; 1e10 where it is not
// finite (a step that blew up is rejected, shrinking).
double scaled_error(const Vec& difference, const Vec& x, const Vec& floor, double tolerance,
                    double divisor = 1.0);

// Landing on regime switches (docs/study.md): a step whose end has an element in another
// regime than its start (Impedance::regime: stuck, sliding, open) is not accepted as it is;
// the switch is located by bisection of the step, the step ends just before it and a short
// one crosses it.
//
// Whether state b has every element in the regime it has at a (signature a_regimes,
// Network::regime_signature with tau), and no slip velocity reversed from a to b.
// part: only that part's elements (Network::regime_signature with the same part).
bool same_regimes(Network& network, const Vec& a, std::size_t a_regimes, const Vec& b, double tau,
                  const Island* part = nullptr);

// Relative precision (of the trial step) to which a change of regime is located.
inline constexpr double kSwitchPrecision = 1e-4;

// The step from (t, x) that lands just before the first change of regime within h:
// bisection on the step length, to within kSwitchPrecision h, where
// take_step(length, probe) advances probe (set to x) by one step of `length` and returns
// false if it could not (counted as past the switch). Regimes are classified with `tau`
// throughout, so that the comparison depends on the state alone. With a part, only its
// elements are compared and only its state entries of probe are set (start_regimes: its
// signature).
double locate_switch(Network& network, double t, double h, const Vec& x, std::size_t start_regimes,
                     double tau, const std::function<bool(double, Vec&)>& take_step, Vec& probe,
                     const Island* part = nullptr);

// The shortest step an adaptive integrator takes at time t before it gives up (below it the
// step is lost in the rounding of t).
double min_adaptive_step(double t);

}  // namespace stiction::core
