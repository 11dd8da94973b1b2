// The problems bench_peers runs in every engine, their physical parameters (the same for all
// engines) and closed forms, and the error measures computed from a recorded trajectory.
//
// Every problem starts at rest on its surface (no drop). The slope is a horizontal plane
// z = 0 under gravity tilted by 20 degrees about y, g = 9.81 (sin 20, 0, -cos 20): the same
// physics as a tilted plane under vertical gravity, and every engine expresses it the same
// way (downhill is +x).
//
// 1. sphere: the paper's Simulation I sphere (m 0.3 kg, R 0.2 m, solid, mu 0.1) resting on
//    the plane, launched at v0 = 2 m/s along x without spin. Slip s = v_x - R w_y falls at
//    (7/2) mu g until it reaches zero at t* = 2 v0 / (7 mu g) = 0.5825 s; the centre then
//    rolls at 5/7 v0.
// 2. slope hold: a box 0.2 x 0.2 x 0.1 m, 1 kg, on its large face, mu 0.5 > tan 20 = 0.364:
//    it must stay. Creep = displacement along the slope over the run and after settling.
// 3. slope slide: the same box, mu 0.2: it slides at a = g (sin 20 - mu cos 20).
//
// Contact stiffness where an engine takes one (stiction; ODE's soft ERP/CFM): the sphere
// K = 1e7 N/m, B = 10 N s/m (scenes/sphere_roll.toml); the box K = 1e6 N/m, B = 1000 N s/m per
// corner (scenes/box_slope.toml).
#pragma once

#include <string>
#include <vector>

namespace stiction::peers {

enum class Problem { sphere, slope_hold, slope_slide };
inline constexpr Problem kProblems[] = {Problem::sphere, Problem::slope_hold, Problem::slope_slide};
std::string problem_name(Problem problem);

inline constexpr double kG = 9.81;
inline constexpr double kSlopeDeg = 20.0;
double slope_rad();
// World gravity of a problem: vertical for the sphere, tilted for the slope problems.
void gravity_of(Problem problem, double g[3]);

struct SphereParams {
  double mass = 0.3, radius = 0.2, mu = 0.1, v0 = 2.0;
  double stiffness = 1e7, damping = 10.0;
};
struct BoxParams {
  double mass = 1.0, size[3] = {0.2, 0.2, 0.1};
  double stiffness = 1e6, damping = 1000.0;  // per corner
};
inline constexpr SphereParams kSphere{};
inline constexpr BoxParams kBox{};
double mu_of(Problem problem);  // the friction coefficient of the problem's contact

// Closed forms.
double sphere_stick_time();
double sphere_final_speed();
double slide_acceleration();

// What the driver records of the body (world frame): at every step for the sphere, every
// sample_interval for the slopes.
struct Sample {
  double t = 0, p[3] = {}, v[3] = {}, w[3] = {};
};

// Durations and sampling of a run (quick: a smoke test, not a measurement).
struct Plan {
  double duration;
  double sample_interval;  // 0: every step
};
Plan plan_of(Problem problem, bool quick);

// Errors of a trajectory: two numbers per problem (NaN where the run failed).
// sphere: stick time error (s), relative final speed error at the end of the run;
// slope_hold: |creep| over the whole run and after settling (from 20 s, or 1 s when quick);
// slope_slide: relative acceleration error from v at two times, and 0.
struct Errors {
  double first = 0, second = 0;
};
Errors measure(Problem problem, const std::vector<Sample>& samples, bool quick);
// Labels of the two numbers for the table.
std::string describe(Problem problem, const Errors& errors);

}  // namespace stiction::peers
