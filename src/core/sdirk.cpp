#include "core/sdirk.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace stiction::core {

double SdirkTableau::c(int r) const {
  double sum = 0.0;
  for (int j = 0; j <= r; ++j) sum += a_at(r, j);
  return sum;
}

const SdirkTableau& sdirk2_tableau() {
  static const SdirkTableau t = [] {
    const double g = 1.0 - 1.0 / std::sqrt(2.0);
    return SdirkTableau{"sdirk2", 2, g, {g, 0.0, 1.0 - g, g}, {1.0, 0.0}, 2, 1};
  }();
  return t;
}

const SdirkTableau& sdirk4_tableau() {
  // Hairer & Wanner, Solving ODEs II, Table IV.6.5 (their code SDIRK4's first method), a
  // row of the tableau a line.
  // clang-format off
  static const SdirkTableau t{"sdirk4",
                              5,
                              0.25,
                              {0.25, 0, 0, 0, 0,                                              //
                               0.5, 0.25, 0, 0, 0,                                            //
                               17.0 / 50, -1.0 / 25, 0.25, 0, 0,                              //
                               371.0 / 1360, -137.0 / 2720, 15.0 / 544, 0.25, 0,              //
                               25.0 / 24, -49.0 / 48, 125.0 / 16, -85.0 / 12, 0.25},
                              {59.0 / 48, -17.0 / 96, 225.0 / 32, -85.0 / 12, 0.0},
                              4,
                              3};
  // clang-format on
  return t;
}

const SdirkTableau& sdirk_tableau_by_name(const std::string& name) {
  for (const SdirkTableau* t : {&sdirk2_tableau(), &sdirk4_tableau()}) {
    if (t->name == name) return *t;
  }
  throw std::invalid_argument("integrator '" + name + "' is not an SDIRK tableau");
}

bool stages_switch(Network& network, const Vec& x, std::size_t x_regimes, const std::vector<Vec>& y,
                   const Island* part) {
  for (const Vec& stage : y) {
    if (!same_regimes(network, x, x_regimes, stage, 0.0, part)) return true;
  }
  return false;
}

double land_before_switch(Network& network, double t, double h, const Vec& x, std::size_t x_regimes,
                          const std::vector<Vec>& y, const std::function<bool(double)>& stages,
                          Vec& probe, const Island* part) {
  const Vec& end = y.back();
  return locate_switch(
      network, t, h, x, x_regimes, 0.0,
      [&](double length, Vec& state) {
        if (!stages(length) || stages_switch(network, x, x_regimes, y, part)) return false;
        if (part != nullptr) {
          for (int e : part->states) state[e] = end[e];
        } else {
          state = end;
        }
        return true;
      },
      probe, part);
}

SwitchWindow window_after_landing(double t, double h) {
  const double floor = 1e-13 * std::max(1.0, std::abs(t));
  return {2.0 * std::max(kSwitchPrecision * h, floor), !(kSwitchPrecision * h > floor)};
}

SdirkStepper::SdirkStepper(const SdirkTableau& tableau, int state_dim, double dt, double tolerance,
                           double max_step)
    : tableau_(tableau),
      implicit_(state_dim, dt),
      dt_(dt),
      tolerance_(tolerance),
      max_step_(max_step),
      h_(std::min(dt, max_step)),
      controller_{integrator_traits(tableau.name).error_order},
      k_(static_cast<std::size_t>(tableau.stages), Vec::Zero(state_dim)),
      y_(static_cast<std::size_t>(tableau.stages), Vec::Zero(state_dim)),
      err_(Vec::Zero(state_dim)),
      floor_(Vec::Ones(state_dim)),
      probe_(Vec::Zero(state_dim)),
      f_start_(Vec::Zero(state_dim)),
      stage_start_(Vec::Zero(state_dim)),
      kept_y_(y_),
      kept_start_(Vec::Zero(state_dim)) {
  implicit_.keep_start_slope(true);
}

bool SdirkStepper::stages(Network& network, double t, double h, const Vec& x) {
  const int s = tableau_.stages;
  const double gh = tableau_.gamma * h;
  bool converged = true;
  for (int r = 0; r < s && converged; ++r) {
    Vec& y = y_[static_cast<std::size_t>(r)];
    y = x;
    for (int j = 0; j < r; ++j) {
      const double a = tableau_.a_at(r, j);
      if (a != 0.0) y.noalias() += (h * a) * k_[static_cast<std::size_t>(j)];
    }
    // The stage's backward Euler step of gamma h ends at t + c_r h.
    converged = implicit_.solve_stage(network, t + (tableau_.c(r) - tableau_.gamma) * h, gh, y);
    if (converged) k_[static_cast<std::size_t>(r)] = implicit_.slope();
    if (r == 0) stage_start_ = implicit_.start_slope();
  }
  evaluations_ = implicit_.evaluations();
  return converged;
}

double SdirkStepper::estimate(double h) {
  const int s = tableau_.stages;
  err_.setZero();
  for (int j = 0; j < s; ++j) {
    const double w = tableau_.a_at(s - 1, j) - tableau_.b_hat[static_cast<std::size_t>(j)];
    if (w != 0.0) err_.noalias() += (h * w) * k_[static_cast<std::size_t>(j)];
  }
  implicit_.apply_inverse(err_);
  return scaled_error(err_, y_[static_cast<std::size_t>(s - 1)], floor_, tolerance_);
}

bool SdirkStepper::step(Network& network, double t, double h, Vec& x) {
  if (!stages(network, t, h, x)) return false;
  x = y_[static_cast<std::size_t>(tableau_.stages - 1)];
  return true;
}

void SdirkStepper::not_converged(double t, double h) const {
  std::ostringstream message;
  message << name() << ": Newton's iteration did not converge in a stage of a step of " << h
          << " s at t = " << t << " s";
  throw std::runtime_error(message.str());
}

double SdirkStepper::accept_fixed(double t, double h, Vec& x) {
  x.swap(y_[static_cast<std::size_t>(tableau_.stages - 1)]);
  f_start_.swap(stage_start_);
  if (off_grid_ && h == grid_end_ - t) off_grid_ = false;
  return h;
}

double SdirkStepper::cross_fixed(Network& network, double t, double h, double regular, double limit,
                                 Vec& x) {
  // Newton's iteration may cycle on the kink of a clamp whose switch lies at the stage's
  // solution: then a longer step, up to the grid point.
  for (;;) {
    const double length = std::min(h, limit);
    if (stages(network, t, length, x)) return accept_fixed(t, length, x);
    if (h >= regular) not_converged(t, length);
    h = std::min(4.0 * h, regular);
  }
}

double SdirkStepper::advance_fixed(Network& network, double t, double limit, Vec& x) {
  // Off the grid (after a landed switch) the step ends at the grid point the cut step was
  // heading to; one within rounding of t is passed for the next.
  if (off_grid_ && grid_end_ - t <= min_adaptive_step(t)) grid_end_ += dt_;
  const double regular = off_grid_ ? grid_end_ - t : dt_;
  if (crossing_) {  // the short step across a located switch, not located again
    crossing_ = false;
    return cross_fixed(network, t, std::min(window_, regular), regular, limit, x);
  }
  const bool refining = refining_;
  refining_ = false;
  const double h = std::min(refining ? std::min(window_, regular) : regular, limit);
  // A window searched again whose step does not converge holds the switch (as a probe of
  // locate_switch that does not converge counts as past it).
  const bool converged = stages(network, t, h, x);
  if (!converged && !refining) {
    // A short step back to the grid just after a switch may cycle on its kink too (a belt's
    // stick 7e-7 s before a point of the grid of 1.25e-4 s: the step from the stick to the
    // grid point did not converge): then the step to the next grid point.
    if (!off_grid_ || regular >= dt_ || h < regular) not_converged(t, h);
    grid_end_ += dt_;
    return advance_fixed(network, t, limit, x);
  }
  // Regimes are classified at each state itself (tau = 0). A stage's clamp, given the
  // stage's start e and tau = gamma h, is the element's law at the stage's solution
  // (|B v + K e| <= F there), so tau = 0 tells which side each stage is on. With tau =
  // gamma h the classification is that of a step of gamma h further: a stuck element's
  // flips gamma h before its breakaway (its slip is F' / K, tau K times that is tau F'), and
  // a step starting closer than that reads as sliding from its start and crosses the
  // breakaway unlanded (measured: the belt's slip onsets then fell on grid points).
  const double tau = 0.0;
  const std::size_t start_regimes = network.regime_signature(x, tau);
  if (converged && !stages_switch(network, x, start_regimes, y_)) return accept_fixed(t, h, x);
  // A probe counts as past the switch when any of its stages is (a higher-order method's
  // stages are off the trajectory near a switch, its end may be back on the old side). The
  // last probe before the switch keeps its stages: the step to the switch.
  double kept = -1.0;
  const double land = locate_switch(
      network, t, h, x, start_regimes, tau,
      [&](double length, Vec& probe) {
        if (!step(network, t, length, probe) || stages_switch(network, x, start_regimes, y_)) {
          return false;
        }
        std::swap(y_, kept_y_);
        kept_start_ = stage_start_;
        kept = length;
        return true;
      },
      probe_);
  if (!refining) ++switches_;
  if (!off_grid_) {
    grid_end_ = t + dt_;
    off_grid_ = true;
  }
  if (land != kept) return cross_fixed(network, t, land, regular, limit, x);  // at t already
  std::swap(y_, kept_y_);
  stage_start_.swap(kept_start_);
  // The switch lies within locate_switch's precision after the landing: that window is
  // searched again, until the precision is at its floor; then a step of the window crosses
  // it.
  const SwitchWindow window = window_after_landing(t, h);
  window_ = window.length;
  (window.crossing ? crossing_ : refining_) = true;
  return accept_fixed(t, land, x);
}

double SdirkStepper::advance(Network& network, double t, double limit, Vec& x) {
  if (!(tolerance_ > 0.0)) return advance_fixed(network, t, limit, x);
  const auto last = static_cast<std::size_t>(tableau_.stages - 1);
  for (;;) {
    const double h = std::min(h_, limit);
    const bool converged = stages(network, t, h, x);
    const double error = converged ? estimate(h) : std::numeric_limits<double>::infinity();
    if (!StepController::accept(error)) {
      ++rejections_;
      // A stage that did not converge: a switch or a stiff transient the step is too long
      // for; a quarter of it.
      h_ = h * (converged ? controller_.factor(error) : 0.25);
      if (h_ < min_adaptive_step(t)) {
        std::ostringstream message;
        message << name() << ": step size underflow at t = " << t << " s ("
                << (converged ? "the error estimate stays above the tolerance"
                              : "Newton's iteration does not converge")
                << ")";
        throw std::runtime_error(message.str());
      }
      continue;
    }
    // A step across a change of regime is cut to end just before it, as the fixed steps'
    // (core/sdirk.hpp says why each part of the landing is needed): regimes at each state
    // itself, a probe past the switch when any of its stages is, the window searched again.
    if (!crossing_) {
      const std::size_t start_regimes = network.regime_signature(x, 0.0);
      if (stages_switch(network, x, start_regimes, y_)) {
        const double land = land_before_switch(
            network, t, h, x, start_regimes, y_,
            [&](double length) { return stages(network, t, length, x); }, probe_);
        if (!refining_) ++switches_;
        if (land < h) {
          if (!stages(network, t, land, x)) {  // the step to the switch
            h_ = 0.25 * land;
            continue;
          }
          last_error_ = estimate(land);
          x.swap(y_[last]);
          f_start_.swap(stage_start_);
          const SwitchWindow window = window_after_landing(t, h);
          crossing_ = window.crossing;
          refining_ = !window.crossing;
          h_ = window.length;
          evaluations_ = implicit_.evaluations();
          return land;
        }
        // The switch is at the step's end: the step stands (y_ holds its stages again only
        // if the last probe was the whole step, so they are computed anew).
        if (!stages(network, t, h, x)) {
          h_ = 0.25 * h;
          continue;
        }
      }
    }
    crossing_ = false;
    refining_ = false;
    last_error_ = error;
    x.swap(y_[last]);
    f_start_.swap(stage_start_);
    // A step cut short by the limit says little about the next one: keep h_ then. A factor
    // of 1..1.2 keeps the step, so that the stages' iteration matrix is reused.
    if (h >= h_) {
      const double factor = controller_.factor(error);
      if (factor < 1.0 || factor > 1.2) h_ = h * factor;
    }
    h_ = std::min(h_, max_step_);
    return h;
  }
}

}  // namespace stiction::core
