#include "core/integrator.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/hermite.hpp"
#include "core/implicit_euler.hpp"
#include "core/island_sdirk.hpp"
#include "core/sdirk.hpp"
#include "core/step_control.hpp"

namespace stiction::core {

const Tableau& euler_tableau() {
  static const Tableau t{"euler", 1, {0.0}, {1.0}, {0.0}, {1.0}, 1};
  return t;
}

const Tableau& heun_tableau() {
  // Explicit trapezoid (RK2): the second stage is taken a full step ahead.
  static const Tableau t{"heun", 2, {0.0, 0.0, 1.0, 0.0}, {0.5, 0.5}, {0.0, 1.0}, {1.0, 1.0}, 2};
  return t;
}

const Tableau& rk4_tableau() {
  // Classic RK4 with the paper's stage sizes {T1..T4} = {T/2, T/2, T, T} (eq. 21).
  static const Tableau t{"rk4",
                         4,
                         {0, 0, 0, 0,    //
                          0.5, 0, 0, 0,  //
                          0, 0.5, 0, 0,  //
                          0, 0, 1, 0},
                         {1.0 / 6, 2.0 / 6, 2.0 / 6, 1.0 / 6},
                         {0.0, 0.5, 0.5, 1.0},
                         {0.5, 0.5, 1.0, 1.0},
                         4};
  return t;
}

const Tableau* find_tableau(const std::string& name) {
  for (const Tableau* t : {&euler_tableau(), &heun_tableau(), &rk4_tableau()}) {
    if (t->name == name) return t;
  }
  return nullptr;
}

const Tableau& tableau_by_name(const std::string& name) {
  if (const Tableau* t = find_tableau(name)) return *t;
  throw std::invalid_argument("integrator '" + name + "' is not an explicit Runge-Kutta tableau");
}

std::unique_ptr<Stepper> make_stepper(const std::string& name, int state_dim, double dt,
                                      double tolerance, double max_step, const Network* network) {
  switch (integrator_traits(name).method) {  // throws for an unknown name
    case Method::explicit_rk:
      return std::make_unique<RungeKuttaStepper>(tableau_by_name(name), state_dim, dt);
    case Method::symplectic_euler:
      return std::make_unique<SymplecticEulerStepper>(state_dim, dt);
    case Method::implicit_euler:
      return std::make_unique<ImplicitEulerStepper>(state_dim, dt);
    case Method::adaptive_rk4:
      if (!(tolerance > 0.0)) throw std::invalid_argument(name + " needs a tolerance > 0");
      return std::make_unique<AdaptiveRk4Stepper>(state_dim, dt, tolerance, max_step);
    case Method::sdirk:
      if (!(tolerance > 0.0)) throw std::invalid_argument(name + " needs a tolerance > 0");
      if (network != nullptr) {
        std::vector<Island> groups = step_groups(*network);
        if (groups.size() > 1) {
          return std::make_unique<IslandSdirkStepper>(
              sdirk_tableau_by_name(name), std::move(groups), state_dim, dt, tolerance, max_step);
        }
      }
      return std::make_unique<SdirkStepper>(sdirk_tableau_by_name(name), state_dim, dt, tolerance,
                                            max_step);
  }
  throw std::logic_error("make_stepper: a method without a stepper");
}

RungeKuttaStepper::RungeKuttaStepper(const Tableau& tableau, int state_dim, double dt)
    : tableau_(tableau), dt_(dt), xi_(tableau.stages, Vec::Zero(state_dim)), stage_x_(state_dim) {
  const int s = tableau_.stages;
  stage_terms_.resize(s);
  for (int r = 0; r < s; ++r) {
    for (int j = 0; j < r; ++j) {
      if (tableau_.a[r * s + j] != 0.0) stage_terms_[r].push_back({j, tableau_.a[r * s + j]});
    }
    if (tableau_.b[r] != 0.0) weights_.push_back({r, tableau_.b[r]});
  }
}

double RungeKuttaStepper::advance(Network& network, double t, double limit, Vec& x) {
  const double h = std::min(dt_, limit);
  step(network, t, h, x);
  return h;
}

void RungeKuttaStepper::combine(const Vec& x, const std::vector<Term>& terms, double T,
                                Vec& out) const {
  auto xi = [&](std::size_t k) -> const Vec& { return xi_[terms[k].stage]; };
  auto c = [&](std::size_t k) { return T * terms[k].coefficient; };
  switch (terms.size()) {
    case 0:
      out = x;
      break;
    case 1:
      out.noalias() = x + c(0) * xi(0);
      break;
    case 2:
      out.noalias() = x + c(0) * xi(0) + c(1) * xi(1);
      break;
    case 3:
      out.noalias() = x + c(0) * xi(0) + c(1) * xi(1) + c(2) * xi(2);
      break;
    case 4:
      out.noalias() = x + c(0) * xi(0) + c(1) * xi(1) + c(2) * xi(2) + c(3) * xi(3);
      break;
    default:
      out = x;
      for (std::size_t k = 0; k < terms.size(); ++k) out.noalias() += c(k) * xi(k);
  }
}

void RungeKuttaStepper::step(Network& network, double t, double T, Vec& x) {
  const int s = tableau_.stages;
  for (int r = 0; r < s; ++r) {
    const double t_stage = t + tableau_.c[r] * T;
    const double tau = T * tableau_.d[r];
    if (stage_terms_[r].empty()) {
      network.derivative_at(t_stage, x.data(), tau, xi_[r].data());  // no copy at x itself
    } else {
      combine(x, stage_terms_[r], T, stage_x_);
      network.derivative_at(t_stage, stage_x_.data(), tau, xi_[r].data());
    }
  }
  evaluations_ += s;
  combine(x, weights_, T, stage_x_);
  x.swap(stage_x_);
  network.project(x);
}

SymplecticEulerStepper::SymplecticEulerStepper(int state_dim, double dt)
    : dt_(dt), xi_(Vec::Zero(state_dim)), rates_(Vec::Zero(state_dim)), start_(state_dim) {}

double SymplecticEulerStepper::advance(Network& network, double t, double limit, Vec& x) {
  const double h = std::min(dt_, limit);
  step(network, t, h, x);
  return h;
}

void SymplecticEulerStepper::step(Network& network, double t, double T, Vec& x) {
  network.derivative(t, x, T, xi_);
  ++evaluations_;
  start_ = x;
  x.noalias() += T * xi_;  // velocities and impedance states: forward Euler
  // Positions: the rates of the new velocities (p_dot = v(k+1), q_dot = Q(w(k+1), q(k))).
  network.kinematics(x, rates_);
  const auto& positions = network.position_slots();
  for (int i = 0; i < x.size(); ++i) {
    if (positions[i]) x[i] = start_[i] + T * rates_[i];
  }
  network.project(x);
}

AdaptiveRk4Stepper::AdaptiveRk4Stepper(int state_dim, double initial_dt, double tolerance,
                                       double max_step)
    : rk4_(rk4_tableau(), state_dim),
      h_(std::min(initial_dt, max_step)),
      tolerance_(tolerance),
      full_(state_dim),
      half_(state_dim),
      mid_(state_dim),
      probe_(state_dim),
      diff_(state_dim),
      floor_(Vec::Ones(state_dim)),
      f_start_(Vec::Zero(state_dim)),
      max_step_(max_step),
      prev_x0_(state_dim),
      prev_f0_(state_dim),
      prev_mid_(state_dim) {}

double AdaptiveRk4Stepper::error_of(Network& network, double t, double h, const Vec& x) {
  full_ = x;
  rk4_.step(network, t, h, full_);
  f_start_ = rk4_.stage_derivative(0);
  half_ = x;
  rk4_.step(network, t, h / 2, half_);
  mid_ = half_;
  rk4_.step(network, t + h / 2, h / 2, half_);
  evaluations_ = rk4_.evaluations();
  // Richardson: the error of the two half steps is about (half - full) / 15.
  diff_.noalias() = half_ - full_;
  return scaled_error(diff_, half_, floor_, tolerance_, 15.0);
}

double AdaptiveRk4Stepper::switch_point(Network& network, double t, double h, const Vec& x,
                                        std::size_t start_regimes) {
  const double at = locate_switch(
      network, t, h, x, start_regimes, h,
      [&](double length, Vec& probe) {
        rk4_.step(network, t, length, probe);
        return true;
      },
      probe_);
  evaluations_ = rk4_.evaluations();
  return at;
}

void AdaptiveRk4Stepper::measure_previous_interpolant(Network& network, const Vec& x) {
  if (!prev_smooth_) return;
  if (body_slots_.empty()) {
    for (int j = 0; j < static_cast<int>(network.admittances().size()); ++j) {
      const Slot s = network.admittance_slot(j);
      for (int i = 0; i < s.state_size; ++i) body_slots_.push_back(s.state_offset + i);
    }
  }
  hermite_state(prev_x0_, prev_f0_, x, f_start_, prev_h_, 0.5, probe_);
  double error = 0.0;
  for (int i : body_slots_) {
    const double scale = tolerance_ * (floor_[i] + std::abs(prev_mid_[i]));
    error = std::max(error, std::abs(probe_[i] - prev_mid_[i]) / scale);
  }
  if (!std::isfinite(error)) return;
  // The interpolant's error grows as h^4.
  dense_cap_ = prev_h_ * std::max(0.9 * std::pow(std::max(error, 1e-10), -0.25), 0.2);
}

void AdaptiveRk4Stepper::remember_step(const Vec& x, double h, bool smooth) {
  prev_x0_ = x;
  prev_f0_ = f_start_;
  prev_mid_ = mid_;
  prev_h_ = h;
  prev_smooth_ = smooth;
}

double AdaptiveRk4Stepper::advance(Network& network, double t, double limit, Vec& x) {
  set_error_floors(network, x, floor_);
  bool first_trial = true;
  for (;;) {
    const double h = std::min(h_, limit);
    const double error = error_of(network, t, h, x);
    const double factor = controller_.factor(error);
    if (first_trial) {
      // The trial's first evaluation is f at the previous step's end: that step's rows can
      // be measured now. A step well past what keeps them is taken again, shorter (the cap
      // also limits the growth below, so this is rare in a smooth phase).
      first_trial = false;
      measure_previous_interpolant(network, x);
      if (h > 1.25 * dense_cap_) {
        h_ = dense_cap_;
        continue;
      }
    }
    if (!StepController::accept(error)) {
      h_ = h * factor;
      if (h_ < min_adaptive_step(t)) {
        throw std::runtime_error("rk4_adaptive: step size underflow");
      }
      continue;
    }
    // A step across a change of regime (an element sticks, slips, touches down or lifts
    // off) is not taken as it is: the two estimates of the error may agree on a wrong
    // answer there (both keep a slow residual slip of a friction element at a large step).
    // The switch is located and the step ends just before it; the next, short step crosses
    // it, and the controller grows the step again from there.
    if (!crossing_) {
      const std::size_t start_regimes = network.regime_signature(x, h);
      if (!same_regimes(network, x, start_regimes, mid_, h) ||
          !same_regimes(network, x, start_regimes, half_, h)) {
        const double land = switch_point(network, t, h, x, start_regimes);
        ++switches_;
        if (land < h) {
          const double taken = land;
          error_of(network, t, taken, x);  // the step to the switch, with its two halves
          remember_step(x, taken, false);  // its end derivative jumps at the switch
          x = half_;
          crossing_ = true;
          h_ = std::max(2.0 * kSwitchPrecision * h, 1e-13 * std::max(1.0, std::abs(t)));
          return taken;
        }
      }
    }
    remember_step(x, h, !crossing_);
    crossing_ = false;
    x = half_;
    // A step cut short by the limit says little about the next one: keep h_ then.
    if (h >= h_) h_ = h * factor;
    h_ = std::min({h_, dense_cap_, max_step_});
    return h;
  }
}

}  // namespace stiction::core
