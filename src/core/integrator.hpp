// Integrators over the network's one state vector. Every one keeps the paper's protocol:
// each evaluation of the network passes the step size tau over which its state
// derivative will be applied, so the impedances (Kikuuwe friction) see the same
// discrete-time model whatever the method.
//
// - Explicit Runge-Kutta methods are data (DESIGN section 6): a tableau drives one stepper.
//   Stage r evaluates the network at x(k) + T sum_j a_rj xi_j, at time kT + c_r T, and
//   passes tau_r = T d_r, where d_r is the fraction of the step over which the stage's
//   derivative is next applied: the paper's {T1..T4}/T = {1/2, 1/2, 1, 1} for RK4 (eq. 21),
//   1 for forward Euler (one stage, tau = T: exactly the discrete model, eq. 14), {1, 1} for
//   Heun. The last stage's d is 1: its derivative is applied over the whole step.
// - Symplectic (semi-implicit) Euler: one evaluation with tau = T updates velocities and
//   impedance states as forward Euler does; positions then move with the new velocities.
// - Adaptive RK4 (step doubling): one step of h and two of h/2, both with the paper's stage
//   sizes for their own step; their difference estimates the error; the two half steps are
//   kept. The step grows or shrinks to keep the error at the tolerance. A step whose end
//   has an element in another regime than its start (Impedance::regime: stuck, sliding,
//   open) is not accepted as it is: the switch is located by bisection of the step, the
//   step ends just before it and a short one crosses it (docs/study.md). Its rows are a
//   cubic Hermite of the state (core/row_sampler.hpp), whose error the stepper also keeps at
//   the tolerance (measured at each step's middle, against the state the step passed
//   through there), and its step is bounded by a few output rows (core/simulation.hpp).
#pragma once

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "core/integrator_traits.hpp"
#include "core/network.hpp"
#include "core/step_control.hpp"

namespace stiction::core {

struct Tableau {
  std::string name;
  int stages = 0;
  std::vector<double> a;  // stages x stages, row-major, strictly lower triangular
  std::vector<double> b;  // weights
  std::vector<double> c;  // stage times
  std::vector<double> d;  // stage step sizes tau_r / T handed to the impedances
  int order = 0;
};

const Tableau& euler_tableau();
const Tableau& heun_tableau();
const Tableau& rk4_tableau();

// The end of a step taken by one part of the network on its own (Stepper::part_step_ends).
struct PartStepEnd {
  double time = 0.0;
  double length = 0.0;  // the step's length
  int segment = 0;      // which of the stepper's kept steps (Stepper::part_step_state)
};

class Stepper {
 public:
  virtual ~Stepper() = default;
  virtual const std::string& name() const = 0;
  virtual int order() const = 0;
  // Advances x from t by one step of at most `limit` (the fixed steppers take
  // min(dt, limit)); returns the step taken. Projects x (quaternions) afterwards.
  virtual double advance(Network& network, double t, double limit, Vec& x) = 0;
  // Number of network evaluations so far (the cost in `stiction study`).
  long evaluations() const { return evaluations_; }
  // Whether advance() evaluates the network first at (t, x) itself, so that what that
  // evaluation computes is the state's own (the run loop reads slips from it).
  virtual bool evaluates_start_first() const { return false; }
  // The state derivative at the start of the step advance() just took, where a variable-step
  // method keeps it for its dense output (core/row_sampler.hpp), or nullptr.
  virtual const Vec* start_derivative() const { return nullptr; }
  // Whether the stepper itself gives the state at times inside the step advance() just took
  // (interpolate), rather than leaving it to a Hermite of the step's two ends: one whose
  // parts take steps of their own within it (core/island_sdirk.hpp).
  virtual bool interpolates() const { return false; }
  // The state at time t inside the last step (t in [start, end]) into x, every entry.
  virtual void interpolate(double /*t*/, Vec& /*x*/) const {}
  // A stepper whose parts take steps of their own: the ends of the steps of the part that
  // holds impedance `impedance` within (t0, t1], oldest first (none from the others)...
  virtual void part_step_ends(int /*impedance*/, double /*t0*/, double /*t1*/,
                              std::vector<PartStepEnd>& ends) const {
    ends.clear();
  }
  // ... and the state at one of them, on that part's entries of x.
  virtual void part_step_state(int /*impedance*/, int /*segment*/, Vec& /*x*/) const {}

 protected:
  long evaluations_ = 0;
};

class RungeKuttaStepper final : public Stepper {
 public:
  RungeKuttaStepper(const Tableau& tableau, int state_dim, double dt = 0.0);
  const std::string& name() const override { return tableau_.name; }
  int order() const override { return tableau_.order; }
  const Tableau& tableau() const { return tableau_; }
  double advance(Network& network, double t, double limit, Vec& x) override;
  bool evaluates_start_first() const override { return true; }  // explicit: stage 1 is at x
  // One step of exactly T from t (no projection skipped), for tests and benchmarks.
  void step(Network& network, double t, double T, Vec& x);
  // Stage r's derivative in the last step (stage 0: at the step's start state).
  const Vec& stage_derivative(int r) const { return xi_[r]; }

 private:
  struct Term {
    int stage;
    double coefficient;
  };
  // x + T sum_j coefficient_j xi_j in one pass over the vector (Eigen fuses up to four
  // terms into a single loop; explicit tableaux rarely need more).
  void combine(const Vec& x, const std::vector<Term>& terms, double T, Vec& out) const;

  Tableau tableau_;
  double dt_;
  std::vector<std::vector<Term>> stage_terms_;  // nonzero a_rj of each stage
  std::vector<Term> weights_;                   // nonzero b_r
  std::vector<Vec> xi_;                         // stage derivatives, allocated once
  Vec stage_x_;
};

class SymplecticEulerStepper final : public Stepper {
 public:
  SymplecticEulerStepper(int state_dim, double dt);
  const std::string& name() const override { return name_; }
  int order() const override { return 1; }
  double advance(Network& network, double t, double limit, Vec& x) override;
  bool evaluates_start_first() const override { return true; }
  void step(Network& network, double t, double T, Vec& x);

 private:
  std::string name_ = "symplectic_euler";
  double dt_;
  Vec xi_, rates_, start_;
};

class AdaptiveRk4Stepper final : public Stepper {
 public:
  // tolerance: mixed absolute/relative bound on the local error of each state entry;
  // max_step: the longest step (simulate: a few output rows, core/simulation.hpp).
  AdaptiveRk4Stepper(int state_dim, double initial_dt, double tolerance,
                     double max_step = std::numeric_limits<double>::infinity());
  const std::string& name() const override { return name_; }
  int order() const override { return 4; }
  double advance(Network& network, double t, double limit, Vec& x) override;
  // The first stage of the accepted step's single step of h: f(t, x; h / 2).
  const Vec* start_derivative() const override { return &f_start_; }
  // Changes of regime located so far (each cost a bisection of the step).
  long switches() const { return switches_; }

 private:
  // One step of h and two of h/2 from x into full_ and half_; the scaled error estimate.
  double error_of(Network& network, double t, double h, const Vec& x);
  // The step from (t, x) that lands just before the first change of regime within h.
  double switch_point(Network& network, double t, double h, const Vec& x,
                      std::size_t start_regimes);
  // Dense output control: once f at the previous step's end is known (x, f_start_), the
  // scaled error of that step's Hermite interpolant at its middle against the state the
  // step itself passed through there (mid_), and from it the longest step whose
  // interpolant keeps the tolerance (dense_cap_).
  // Only the bodies' states are measured: they are what the rows show, while an impedance's
  // state (a friction spring's e, of natural size F / K) moves on its own fast scale, which
  // the step's error test already holds to the tolerance.
  void measure_previous_interpolant(Network& network, const Vec& x);
  // Keeps what measure_previous_interpolant needs of the step just accepted from x.
  void remember_step(const Vec& x, double h, bool smooth);

  std::string name_ = "rk4_adaptive";
  RungeKuttaStepper rk4_;
  double h_;
  double tolerance_;
  Vec full_, half_, mid_, probe_;  // mid_: after the first half step
  Vec diff_;                       // half_ - full_
  Vec floor_;                      // core/step_control.hpp's error floors
  StepController controller_{integrator_traits("rk4_adaptive").error_order};
  Vec f_start_;  // start_derivative()
  double max_step_;
  // The previous step (start, start derivative, middle, length), whether its interpolant is
  // measured (not across a regime switch, where the derivatives jump), and the step cap.
  Vec prev_x0_, prev_f0_, prev_mid_;
  double prev_h_ = 0.0;
  bool prev_smooth_ = false;
  std::vector<int> body_slots_;  // the admittances' state entries
  double dense_cap_ = std::numeric_limits<double>::infinity();
  bool crossing_ = false;  // the next step crosses a located switch: not located again
  long switches_ = 0;
};

// euler | symplectic_euler | heun | rk4 | implicit use dt (implicit: core/implicit_euler.hpp);
// the adaptive ones (rk4_adaptive; sdirk2, sdirk4: core/sdirk.hpp) use dt as their first step
// and need tolerance > 0. Throws std::invalid_argument naming the known integrators.
// max_step bounds an adaptive integrator's step (the others ignore it). Given the network,
// sdirk2 and sdirk4 on a network of several step groups step each group on its own
// (core/island_sdirk.hpp); without it, the whole network on one step.
std::unique_ptr<Stepper> make_stepper(const std::string& name, int state_dim, double dt,
                                      double tolerance = 0.0,
                                      double max_step = std::numeric_limits<double>::infinity(),
                                      const Network* network = nullptr);
// The tableau of an explicit RK integrator name, or nullptr (symplectic Euler, adaptive).
const Tableau* find_tableau(const std::string& name);
// Same, but throws std::invalid_argument for a name without a tableau.
const Tableau& tableau_by_name(const std::string& name);

}  // namespace stiction::core
