// `--integrator sdirk2` and `--integrator sdirk4`: L-stable, stiffly accurate singly diagonally
// implicit Runge-Kutta methods with an embedded error estimate and step-size control at
// `--tolerance`, built on the backward Euler stage of core/implicit_euler.hpp.
//
// A step of h from (t, x), stages r = 1..s of the tableau (a_rj, a_rr = gamma, c_r):
//   z_r = x + h sum_{j<r} a_rj k_j
//   y_r = z_r + gamma h k_r,  k_r = F(t + c_r h, y_r*; tau = gamma h)
// so each stage is a backward Euler step of gamma h from its own start z_r
// (ImplicitEulerStepper::solve_stage), every impedance is passed tau = gamma h, and x(k+1) =
// y_s (stiffly accurate: the last row of a is the weights b). Kikuuwe's friction law with
// tau = gamma h is that stage's backward Euler step of its own spring in closed form, so a
// stuck element's state and the position it holds move by the same combination of slopes
// (k_r of the state is the slip velocity at y_r, as k_r of the position): its anchor does
// not drift, as under the paper's RK4 and the implicit Euler step.
//
// Error control: the embedded solution x^ = x + h sum_j bhat_j k_j (order p^ = order - 1)
// gives the local error estimate err = x(k+1) - x^, filtered as Hairer and Wanner do,
// (I - gamma h J)^-1 err with the stages' iteration matrix (Solving ODEs II, IV.8: the plain
// difference grows as h J on stiff modes, the filtered one stays bounded), held at the
// tolerance by core/step_control.hpp's controller (error order p^ + 1), every entry mixed
// absolute/relative (floor 1), a clamped friction element's state e included: it is in the
// unit of the motion it follows (m, rad), and moves with it while stuck. (rk4_adaptive
// measures e against its natural size F / K instead, step_control.hpp's error floors, which
// holds the ringing of a stuck element's stiff spring, amplitude F / K, to the tolerance
// times F / K: thousands of steps of a few microseconds after the sphere sticks, where this
// L-stable method damps it within the tolerance of the velocities. A switch the step would
// jump over, e swinging from +F/K to -F/K, is landed on instead.) A trial step whose
// stages do not converge is retried at a quarter of its length. A next step within 1..1.2
// times the last keeps the last (its iteration matrix is reused).
//
// Regime switches are landed on, at error-controlled and at fixed steps alike (below,
// land_before_switch): a step with any stage solution y_r in another regime than x, or a
// sliding element whose slip reversed there, is cut to end just before the switch
// (core/step_control.hpp's locate_switch); the window of locate_switch's precision (1e-4 of
// the step) in which the switch then lies is searched again until it is at rounding, and a
// step of that window crosses it. Each part is needed (docs/study.md, "sdirk2, sdirk4"):
// - regimes are classified at the state itself (tau = 0: the clamp a stage obeys); with tau
//   = gamma h a stuck element reads as sliding gamma h before its breakaway, and a step
//   starting there crosses it unlanded;
// - a probe of the bisection is past the switch when any of its stages is (sdirk4's inner
//   stages cross before its end does, which may even come back);
// - the window is an error of first order (the force's jump times the window): at fixed
//   steps it makes every method first order; error-controlled, a step of it across a belt's
//   breakaway (1e-6 s after steps of 5e-3 s) left the velocity 1.3e-6 m/s off, within the
//   tolerance 1e-6, but through the contact's damping (2500 N s/m) that held the element
//   stuck for another 9e-5 s.
// Without them, error-controlled runs of generated belts ended up to 1.2e-3 m off at
// tolerance 1e-6 and 2e-4 m at 1e-8; with them within 5 tolerances
// (tests/physics/test_sdirk.cpp).
//
// Fixed steps (tolerance 0, for measuring the order) land on switches too, or the error of
// the step across each switch (the force's jump times the step) would make every method
// first order on stick-slip; after a landing they return to the grid of multiples of dt
// from the run's start.
//
// Tableaux:
// - sdirk2: Alexander (1977), gamma = 1 - 1/sqrt(2), c = (gamma, 1), b = (1 - gamma, gamma);
//   embedded bhat = (1, 0) (first order), err = gamma h (k2 - k1).
// - sdirk4: Hairer & Wanner, Solving ODEs II, Table IV.6.5 (gamma = 1/4, 5 stages, order 4,
//   L-stable, stiffly accurate), with its embedded third-order solution.
#pragma once

#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "core/implicit_euler.hpp"
#include "core/integrator.hpp"
#include "core/step_control.hpp"

namespace stiction::core {

struct SdirkTableau {
  std::string name;
  int stages = 0;
  double gamma = 0.0;
  std::vector<double> a;      // stages x stages, row-major, lower triangular, a_rr = gamma
  std::vector<double> b_hat;  // the embedded solution's weights (b is a's last row)
  int order = 0;
  int embedded_order = 0;
  double a_at(int r, int j) const { return a[static_cast<std::size_t>(r * stages + j)]; }
  double c(int r) const;  // sum_j a_rj
};

const SdirkTableau& sdirk2_tableau();
const SdirkTableau& sdirk4_tableau();
// The tableau of an SDIRK integrator name; throws std::invalid_argument for another name.
const SdirkTableau& sdirk_tableau_by_name(const std::string& name);

// Landing on regime switches, shared by SdirkStepper's steps (fixed and error-controlled) and
// IslandSdirkStepper's (part: a step group's elements and state entries; nullptr: the whole
// network). Regimes are classified at each state itself, tau = 0 (core/sdirk.cpp says why).
//
// Whether any stage solution in y (all the stages of a step from x) is in another regime
// than x (signature x_regimes, Network::regime_signature at tau 0 with the same part), or
// has a sliding element's slip reversed.
bool stages_switch(Network& network, const Vec& x, std::size_t x_regimes, const std::vector<Vec>& y,
                   const Island* part = nullptr);
// The length of the step from (t, x) that ends just before the first switch within h
// (core/step_control.hpp's locate_switch), where stages(length) computes into y the stages
// of a step of that length from x, false if one did not converge. A probe counts as past
// the switch when its stages did not converge or any of them is past (sdirk4's inner stages
// cross before its end does, and the end may come back to the old side).
double land_before_switch(Network& network, double t, double h, const Vec& x, std::size_t x_regimes,
                          const std::vector<Vec>& y, const std::function<bool(double)>& stages,
                          Vec& probe, const Island* part = nullptr);
// After a step landed just before a switch located within a trial step of h at t: the
// switch lies in a window of locate_switch's precision (1e-4 h) from there. Its error is of
// first order (the force's jump times the window), so the window is searched again (the
// next step's length, crossing false) until the precision is at rounding; then a step of the
// window crosses it (crossing true, not located again).
struct SwitchWindow {
  double length;
  bool crossing;
};
SwitchWindow window_after_landing(double t, double h);

class SdirkStepper final : public Stepper {
 public:
  // tolerance > 0: error-controlled steps starting from dt, at most max_step; tolerance 0:
  // fixed steps of dt without error control (for measuring the order), landing on switches
  // (above): a step whose stages change regime is cut to end just before the switch, a
  // short step crosses it, and the next ends on the grid of multiples of dt again (so
  // halving dt halves every regular step). Without switches, steps of exactly dt.
  SdirkStepper(const SdirkTableau& tableau, int state_dim, double dt, double tolerance,
               double max_step = std::numeric_limits<double>::infinity());
  const std::string& name() const override { return tableau_.name; }
  int order() const override { return tableau_.order; }
  double advance(Network& network, double t, double limit, Vec& x) override;
  // The first stage's first evaluation is at (t + gamma h, x) itself.
  bool evaluates_start_first() const override { return true; }
  // F(t + gamma h, x; gamma h) at the start x of the step advance() just took.
  const Vec* start_derivative() const override { return &f_start_; }

  // One step of exactly h from t into x, without error control; false (x unchanged) if a
  // stage's Newton iteration did not converge.
  bool step(Network& network, double t, double h, Vec& x);
  // The filtered, scaled error estimate of the last step advance() accepted (tolerance > 0).
  double last_error() const { return last_error_; }
  long switches() const { return switches_; }      // changes of regime landed on
  long rejections() const { return rejections_; }  // trial steps rejected

 private:
  // The stages of a step of h from (t, x): y_[r], k_[r]; false if one did not converge.
  bool stages(Network& network, double t, double h, const Vec& x);
  // The scaled, filtered error estimate of the stages just computed (step h, start x).
  double estimate(double h);
  // Throws std::runtime_error: a fixed step of h from t whose stages did not converge.
  [[noreturn]] void not_converged(double t, double h) const;
  // Takes the stages just computed (step h from t) as the step; h.
  double accept_fixed(double t, double h, Vec& x);
  // A fixed step across a switch at t: h, or longer (up to `regular`) if its stages do not
  // converge.
  double cross_fixed(Network& network, double t, double h, double regular, double limit, Vec& x);
  // advance() at tolerance 0: fixed steps on the grid, landing on switches.
  double advance_fixed(Network& network, double t, double limit, Vec& x);

  SdirkTableau tableau_;
  ImplicitEulerStepper implicit_;
  double dt_;
  double tolerance_;
  double max_step_;
  double h_;
  StepController controller_;
  std::vector<Vec> k_, y_;             // stage slopes and solutions, allocated once
  Vec err_, floor_, probe_, f_start_;  // floor_: ones (see above)
  Vec stage_start_;                    // the start slope of the stages last computed
  double last_error_ = 0.0;
  // After a landing: the next step searches the window in which the switch lies again
  // (refining_), or crosses it (crossing_: not located again).
  bool crossing_ = false;
  bool refining_ = false;
  // Fixed steps: that window; whether (off_grid_) the steps are heading back to the grid
  // point grid_end_ after a landed switch.
  double window_ = 0.0;
  std::vector<Vec> kept_y_;  // the stages of the last probe before a switch
  Vec kept_start_;
  bool off_grid_ = false;
  double grid_end_ = 0.0;
  long switches_ = 0;
  long rejections_ = 0;
};

}  // namespace stiction::core
