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
// 4. N spheres (issue 36): N copies of the sphere of problem 1, each on its own lane of the
//    plane (0.5 m apart: they never touch each other, so every sphere has its own contact
//    and nothing else), launched at v0 spread evenly over 1..3 m/s, so that their stick
//    times 2 v0 / (7 mu g) spread over 0.29..0.87 s and the spheres switch regime one at a
//    time. N = 1 is problem 1's sphere (v0 = 2 m/s). What scales with N is measured: CPU per
//    simulated second, and each sphere's stick time against its closed form (relative).
// 5. pendulum: a 0.5 x 0.03 x 0.03 m, 1 kg bar hanging from a horizontal hinge (axis -y at
//    the origin, so the angle phi from hanging straight down grows towards +x) with Coulomb
//    joint friction F = 0.02 N m, released at rest 0.2 rad from the bottom: it swings, each
//    half swing F / (m g l_c) smaller, and stops for good at a turning point inside the
//    friction band |m g l_c sin phi| <= F (scenes/pendulum_friction.toml's pendulum). The
//    reference is the ideal Coulomb pendulum integrated here by rk4 at 1e-5 s, landing on
//    every turning point (pendulum_reference.cpp); the measures are the turning points'
//    times (phase) and angles (amplitude), the rest angle and the stop time.
//
// 6. ramp_grid (issue 38): problem 2's box on a ramp of angle a, friction mu, over a grid:
//    mu in kRampMus and tan a / mu in kRampRatios (all below 1: it must hold). Creep = the
//    speed along the slope after settling, |x(end) - x(settle)| / (end - settle). Per mu, the
//    breakaway angle is found by bisection (Case::breakaway): the smallest angle at which
//    the box moves faster than kBreakawaySpeed on average over [settle, settle + 2 s];
//    its error against atan mu says whether the box holds just below atan mu and slides just
//    above it. Untimed (a bisection's run count depends on the engine).
// 7. pinch (issue 38): a 0.1 m cube of 1 kg pinched between two fingers (0.02 x 0.15 x
//    0.15 m boxes of 0.5 kg on either side along x) under vertical gravity, mu 0.5 between
//    block and finger; each finger pressed towards the block by F = margin m g / (2 mu),
//    margin in kPinchMargins (the squeeze's holding margin, 1.1x to 20x). The peers' fingers
//    slide along x on a prismatic joint (each engine's gripper); stiction's stand on a
//    frictionless floor (mu 0) with a force source each, so the floor carries them.
//    Creep = the block's vertical speed relative to the fingers after settling. Contact
//    K = 1e6 N/m, B = 100 N s/m per point (stiction, ODE): the box's B = 1000 would damp the
//    light fingers' rotation at -4.6 / (1e-4 s), past rk4's stability limit, and the
//    fingers then chatter in their guides and let the block creep (2-4e-4 m/s, measured).
//
// Contact stiffness where an engine takes one (stiction; ODE's soft ERP/CFM): the sphere
// K = 1e7 N/m, B = 10 N s/m (scenes/sphere_roll.toml); the box K = 1e6 N/m, B = 1000 N s/m per
// corner (scenes/box_slope.toml).
#pragma once

#include <ctime>
#include <limits>
#include <string>
#include <vector>

namespace stiction::peers {

// CPU time of the calling thread (s): what each engine's stepping costs, whatever else runs.
inline double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

enum class Problem { sphere, slope_hold, slope_slide, spheres, pendulum, ramp_grid, pinch };
std::string problem_name(Problem problem);

// A problem and its size: the number of spheres of Problem::spheres (1 for every other).
// ramp_grid: mu, the ramp angle (rad) and whether this case is the breakaway search (angle
// unused); pinch: mu and the holding margin.
struct Case {
  Problem problem = Problem::sphere;
  int count = 1;
  double mu = 0.0, angle = 0.0, margin = 0.0;
  bool breakaway = false;
};
std::string case_name(const Case& c);

inline constexpr double kG = 9.81;
inline constexpr double kSlopeDeg = 20.0;
double slope_rad();
// World gravity of a case: vertical for the sphere and the pinch, tilted for the slopes and
// the ramp (its case's angle).
void gravity_of(const Case& c, double g[3]);
// Whether the case is problem 2's box on the (tilted) plane: slope_hold, slope_slide, ramp.
bool box_on_plane(Problem problem);

struct SphereParams {
  double mass = 0.3, radius = 0.2, mu = 0.1, v0 = 2.0;
  double stiffness = 1e7, damping = 10.0;
};
struct BoxParams {
  double mass = 1.0, size[3] = {0.2, 0.2, 0.1};
  double stiffness = 1e6, damping = 1000.0;  // per corner
};
struct PendulumParams {
  double mass = 1.0, length = 0.5, width = 0.03;  // a bar of square section
  double friction = 0.02;                           // N m: Coulomb joint friction F
  double angle0 = 0.2;                              // rad from hanging straight down
  // stiction's Kikuuwe joint friction element (scenes/pendulum.toml): its stick stiffness
  // and damping (the other engines take F alone).
  double stiffness = 5000.0, damping = 1.0;
  double com() const { return 0.5 * length; }
  // Moment of inertia about the hinge: the bar's own about its centre plus m l_c^2.
  double inertia() const {
    return mass * (length * length + width * width) / 12.0 + mass * com() * com();
  }
};
inline constexpr SphereParams kSphere{};
inline constexpr BoxParams kBox{};
inline constexpr PendulumParams kPendulum{};
struct PinchParams {
  double mass = 1.0, size = 0.1;                    // the block, a cube
  double finger_mass = 0.5, finger[3] = {0.02, 0.15, 0.15};
  double mu = 0.5;
  double stiffness = 1e6, damping = 100.0;  // per contact point (stiction, ODE)
  double height = 0.075;                     // the centres' z: stiction's fingers stand on z = 0
  // The force on each finger for a holding margin: 2 mu F = margin m g.
  double squeeze(double margin) const { return margin * mass * kG / (2.0 * mu); }
  // The fingers' centres at x = -+finger_x() when they just touch the block.
  double finger_x() const { return 0.5 * (size + finger[0]); }
  // How far the peers' fingers start inside the block (m): touching exactly, ODE and DART at
  // 1/60 s find no contact at the first step and the fingers pass through the block at 20x
  // (0.11 m in one step). stiction's start at its static deflection, F / (4 K).
  double start_overlap = 5e-4;
};
inline constexpr PinchParams kPinch{};
inline constexpr double kRampMus[] = {0.1, 0.2, 0.3, 0.5, 0.7, 1.0};
inline constexpr double kRampRatios[] = {0.25, 0.5, 0.75, 0.9, 0.99};  // tan a / mu
inline constexpr double kPinchMargins[] = {1.1, 1.5, 2.0, 5.0, 20.0};
inline constexpr double kBreakawaySpeed = 1e-3;  // m/s: faster on average is sliding
inline constexpr double kLaneSpacing = 0.5;  // m between the lanes of the N spheres
double mu_of(Problem problem);  // the friction coefficient of the problem's contact
double mu_of(const Case& c);    // the case's (ramp_grid, pinch) or else the problem's

// Sphere i of n (problem 4): launch speed along x and lane (y of its centre).
double spheres_v0(int i, int n);
double spheres_lane(int i);

// Closed forms.
double sphere_stick_time();
double stick_time_of(double v0);  // 2 v0 / (7 mu g), the sphere's mu
double sphere_final_speed();
double slide_acceleration();

// What the driver records of a body (world frame): at every step for the sphere and the
// pendulum (its bar), every sample_interval for the slopes; the N spheres are watched every
// step by a StickWatch each instead of being recorded.
struct Sample {
  double t = 0, p[3] = {}, v[3] = {}, w[3] = {};
};

// Durations and sampling of a run (quick: a smoke test, not a measurement).
struct Plan {
  double duration;
  double sample_interval;  // 0: every step
};
Plan plan_of(Problem problem, bool quick);
// The angle (rad) at which an ideal Coulomb box on the ramp passes the breakaway test: it
// slides from t = 0 at g (sin a - mu cos a), so its mean speed over [settle, end] is that
// times (settle + end) / 2; the breakaway error is measured against this angle (a hair
// above atan mu: 0.0029 degrees at mu 0.1), not against atan mu itself.
double breakaway_reference(double mu, bool quick);
// Settling time of the hold problems (ramp_grid, pinch): creep is measured after it.
double settle_time(bool quick);
// The breakaway search's runs: their duration (settle + the averaging window).
double breakaway_duration(bool quick);

// Errors of a run: up to three numbers per problem (NaN where the run failed).
// sphere: stick time error (s), relative final speed error at the end of the run;
// slope_hold: |creep| over the whole run and after settling (from 20 s, or 1 s when quick);
// slope_slide: relative acceleration error from v at two times, and 0;
// spheres: the largest |relative stick time error| over the spheres, the mean of them, and
//   the number of spheres that never stuck (their error is not in the first two);
// pendulum: the largest |time error| over the turning points (phase), the largest |angle
//   error| over the turning points and the rest angle (amplitude), the stop time error;
//   `note` says when the engine turned a different number of times than the reference.
struct Errors {
  double first = 0, second = 0, third = 0;
  std::string note = {};
};
Errors measure(Problem problem, const std::vector<Sample>& samples, bool quick);
// ramp_grid (body 0) and pinch (bodies 0, 1, 2): creep in m/s after settling, the
// displacement over the whole run (m), and for the pinch the block's drop relative to the
// fingers (m, positive down). samples[b] is body b's record.
Errors measure_hold(const Case& c, const std::vector<std::vector<Sample>>& samples, bool quick);
// The ramp grid's cases (creep: mus x ratios; then one breakaway case per mu) and the
// pinch's (one per margin); quick: one of each.
std::vector<Case> ramp_cases(bool quick);
std::vector<Case> pinch_cases(bool quick);
// Labels of the numbers for the table.
std::string describe(Problem problem, const Errors& errors);

// The slip of the sphere at a sample, v_x - R w_y.
double slip_of(const Sample& s);

// Follows one sphere's slip sample by sample, as stick_time() reads a recorded trajectory:
// sliding while the slip exceeds half of one step's fall; the stick time is where the line
// through the last two sliding samples crosses zero. O(1) per sample, so a thousand spheres
// at 1e-4 s need no recording.
class StickWatch {
 public:
  explicit StickWatch(double dt) : threshold_(0.5 * 3.5 * kSphere.mu * kG * dt) {}
  void add(double t, double slip);
  double stick_time() const { return stick_time_; }  // NaN until it sticks

 private:
  double threshold_;
  double t0_ = 0, s0_ = 0, t1_ = 0, s1_ = 0;
  int sliding_ = 0;  // sliding samples seen (0, 1, 2 = enough for the line)
  bool done_ = false;
  double stick_time_ = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace stiction::peers
