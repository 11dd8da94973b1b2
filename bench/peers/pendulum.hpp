// The pendulum with joint friction (problem 5 of problems.hpp): its reference, the ideal
// Coulomb pendulum, and what is compared: the turning points (where the bar's rate crosses
// zero), the stop (the turning point after which it never moves again) and the rest angle.
#pragma once

#include <vector>

#include "problems.hpp"

namespace stiction::peers {

struct TurningPoint {
  double t = 0, angle = 0;  // angle from hanging straight down, rad
};

struct Swings {
  std::vector<TurningPoint> turns;  // in time order; the stop is the last when it stopped
  double stop_time = std::numeric_limits<double>::quiet_NaN();  // NaN: still moving
  double rest_angle = std::numeric_limits<double>::quiet_NaN();  // angle at the end
  bool creeping = false;  // came to rest without a turning point (a soft stick that creeps)
};

// The bar's angle from hanging straight down and its rate about the hinge axis (-y), from a
// sample of its centre of mass and angular velocity (pivot at the origin).
double pendulum_angle(const Sample& s);
double pendulum_rate(const Sample& s);

// The ideal Coulomb pendulum of kPendulum over [0, duration]: I phi'' = -m g l_c sin phi
// - F sign(phi'), integrated by rk4 at 1e-5 s on each smooth piece (a constant sign of the
// rate), every turning point found by bisection to rounding; at a turning point inside the
// friction band it stops for good. Computed once per duration.
const Swings& pendulum_reference(double duration);

// An engine's swings from its samples (every step). A swing counts while the rate exceeds
// kMoving in magnitude; its turning point is where the line through its last two samples
// crosses zero (the acceleration just before the turn; past it, the friction torque has
// changed sign), the angle there from the same constant acceleration.
// rad/s: the reference's slowest swing (the last) peaks near 0.065 rad/s, and a stuck joint
// whose stick is a stiff spring (stiction's Kikuuwe element) rings at up to ~2e-3 rad/s.
inline constexpr double kMoving = 1e-2;
Swings swings_of(const std::vector<Sample>& samples);

// phase: largest |time error| over the turning points both have; amplitude: largest |angle
// error| over them and the rest angle; stop time error (NaN if either has not stopped).
Errors compare_swings(const Swings& engine, const Swings& reference);

}  // namespace stiction::peers
