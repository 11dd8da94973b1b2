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
// times the last keeps the last (its iteration matrix is reused). Regime switches are landed
// on as rk4_adaptive lands on them (core/step_control.hpp): any stage solution y_r in another
// regime than x, or a sliding element whose slip reversed there, and the step is cut to end
// just before the switch; a short step crosses it.
//
// Tableaux:
// - sdirk2: Alexander (1977), gamma = 1 - 1/sqrt(2), c = (gamma, 1), b = (1 - gamma, gamma);
//   embedded bhat = (1, 0) (first order), err = gamma h (k2 - k1).
// - sdirk4: Hairer & Wanner, Solving ODEs II, Table IV.6.5 (gamma = 1/4, 5 stages, order 4,
//   L-stable, stiffly accurate), with its embedded third-order solution.
#pragma once

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

class SdirkStepper final : public Stepper {
 public:
  // tolerance > 0: error-controlled steps starting from dt, at most max_step; tolerance 0:
  // fixed steps of dt without error control (for measuring the order).
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

  SdirkTableau tableau_;
  ImplicitEulerStepper implicit_;
  double dt_;
  double tolerance_;
  double max_step_;
  double h_;
  StepController controller_;
  std::vector<Vec> k_, y_;  // stage slopes and solutions, allocated once
  Vec err_, floor_, probe_, f_start_;  // floor_: ones (see above)
  Vec stage_start_;  // the start slope of the stages last computed
  double last_error_ = 0.0;
  bool crossing_ = false;  // the next step crosses a located switch: not located again
  long switches_ = 0;
  long rejections_ = 0;
};

}  // namespace stiction::core
