#include "core/stability.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include "core/integrator.hpp"

namespace stiction::core {
namespace {

// Headroom of the energy monitor (simulation.cpp) at a state of energy `energy`, with
// `work` done by sources so far.
double headroom(const RunOptions& options, double initial_energy, double energy, double work) {
  if (!std::isfinite(initial_energy) || !std::isfinite(energy)) return INFINITY;  // unmonitored
  return energy_margin(options, initial_energy, work) - (energy - initial_energy);
}

// Runs the scene at its options and calls visit(step, t, x, work) before every step.
template <typename Visit>
void walk_run(Network& network, const RunOptions& options, Visit visit) {
  auto stepper = make_stepper(options.integrator, network.state_dim(), options.dt,
                              options.tolerance);
  Vec x = network.initial_state();
  double t = 0.0, work = 0.0;
  const bool sources = network.has_sources();
  double power = sources ? std::abs(network.source_power(0.0, x)) : 0.0;
  for (long k = 0; t < options.duration; ++k) {
    if (options.stop != nullptr && options.stop->load(std::memory_order_relaxed)) break;
    visit(k, t, x, work);
    const double h = stepper->advance(network, t, options.duration - t, x);
    t += h;
    if (!x.allFinite()) break;
    if (sources) {
      const double p = std::abs(network.source_power(t, x));
      work += 0.5 * (power + p) * h;
      power = p;
    }
  }
}

// dF/dx at x by central differences, F(at, out) any map of the state. Empty where x lies on
// a switching surface of some element (the one-sided differences disagree at every
// perturbation size tried).
template <typename Function>
std::optional<Eigen::MatrixXd> central_jacobian(const Function& F, const Vec& x) {
  const int n = static_cast<int>(x.size());
  Eigen::MatrixXd J(n, n);
  Vec center(n), plus(n), minus(n), f_plus(n), f_minus(n);
  F(x, center);
  for (int i = 0; i < n; ++i) {
    // A state near a switching surface (a contact barely closed, friction near its limit)
    // needs a perturbation smaller than its distance to the surface: try finer ones before
    // giving up. Rounding limits the finest to about 1e-5 relative accuracy, enough here.
    bool smooth = false;
    for (double relative : {1e-7, 1e-9, 1e-11}) {
      const double delta = relative * std::max(std::abs(x[i]), 1e-3);
      plus = x;
      plus[i] += delta;
      minus = x;
      minus[i] -= delta;
      F(plus, f_plus);
      F(minus, f_minus);
      const Vec forward = (f_plus - center) / delta;
      const Vec backward = (center - f_minus) / delta;
      const double scale =
          1.0 + forward.lpNorm<Eigen::Infinity>() + backward.lpNorm<Eigen::Infinity>();
      if ((forward - backward).lpNorm<Eigen::Infinity>() <= 1e-4 * scale) {
        J.col(i) = 0.5 * (forward + backward);
        smooth = true;
        break;
      }
    }
    if (!smooth) return std::nullopt;
  }
  return J;
}

// J = dF/dx at (t, x; tau), with clamping friction held at its value at x if asked.
std::optional<Eigen::MatrixXd> jacobian(Network& network, double t, const Vec& x, double tau,
                                        bool friction_held) {
  return central_jacobian(
      [&](const Vec& at, Vec& out) {
        if (friction_held) {
          network.derivative_friction_held(t, at, tau, out, x);
        } else {
          network.derivative(t, at, tau, out);
        }
      },
      x);
}

// Linear step map of a Runge-Kutta tableau from the Jacobians at its stage sizes.
std::optional<Eigen::MatrixXd> rk_step_map(Network& network, const Tableau& tab, double t,
                                           const Vec& x, double h, bool friction_held) {
  const int n = static_cast<int>(x.size());
  const int s = tab.stages;
  std::map<double, Eigen::MatrixXd> by_tau;  // one Jacobian per distinct stage size
  std::vector<Eigen::MatrixXd> K(s);
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n);
  Eigen::MatrixXd phi = I;
  for (int r = 0; r < s; ++r) {
    const double tau = h * tab.d[r];
    auto it = by_tau.find(tau);
    if (it == by_tau.end()) {
      auto J = jacobian(network, t, x, tau, friction_held);
      if (!J) return std::nullopt;
      it = by_tau.emplace(tau, std::move(*J)).first;
    }
    Eigen::MatrixXd stage = I;
    for (int j = 0; j < r; ++j) {
      if (tab.a[r * s + j] != 0.0) stage += h * tab.a[r * s + j] * K[j];
    }
    K[r] = it->second * stage;
    phi += h * tab.b[r] * K[r];
  }
  return phi;
}

// Symplectic Euler: x' = x + h F(x; h), then the positions move with the new velocities,
// p(k+1) = p(k) + h G(x'), G the admittances' kinematics.
std::optional<Eigen::MatrixXd> symplectic_step_map(Network& network, double t, const Vec& x,
                                                   double h, bool friction_held) {
  const int n = static_cast<int>(x.size());
  auto J = jacobian(network, t, x, h, friction_held);
  if (!J) return std::nullopt;
  const Eigen::MatrixXd A = Eigen::MatrixXd::Identity(n, n) + h * *J;
  // G's Jacobian: the kinematics are smooth (p_dot = v, q_dot = Q(w) q).
  const auto G = central_jacobian(
      [&](const Vec& at, Vec& out) { network.kinematics(at, out); }, x);
  if (!G) return std::nullopt;
  Eigen::MatrixXd phi = A;
  const Eigen::MatrixXd moved = h * *G * A;
  const auto& positions = network.position_slots();
  for (int i = 0; i < n; ++i) {
    if (!positions[i]) continue;
    phi.row(i) = moved.row(i);
    phi(i, i) += 1.0;
  }
  return phi;
}

double spectral_radius(const Eigen::MatrixXd& phi) {
  if (!phi.allFinite()) return INFINITY;
  return Eigen::EigenSolver<Eigen::MatrixXd>(phi, false).eigenvalues().cwiseAbs().maxCoeff();
}

}  // namespace

std::vector<TimedState> sample_states(Network& network, const RunOptions& options,
                                      int per_regime) {
  // Pass 1: how many steps each regime lasts. Pass 2 (the same deterministic run): take
  // per_regime of them, evenly spread.
  std::map<std::size_t, long> steps_in;
  walk_run(network, options, [&](long, double, const Vec& x, double) {
    ++steps_in[network.regime_signature(x, options.dt)];
  });
  std::map<std::size_t, long> seen;
  std::vector<TimedState> states;
  const double initial_energy = network.energy(network.initial_state());
  walk_run(network, options, [&](long, double t, const Vec& x, double work) {
    const std::size_t regime = network.regime_signature(x, options.dt);
    const long total = steps_in[regime];
    const long index = seen[regime]++;
    // Taken where index * per_regime / total (integer division) moves on: per_regime steps
    // evenly spread, or every step of a regime shorter than that.
    const long n = std::max(1, per_regime);
    if (index == 0 || (index * n) / total != ((index - 1) * n) / total) {
      states.push_back({t, x, headroom(options, initial_energy, network.energy(x), work)});
    }
  });
  std::sort(states.begin(), states.end(),
            [](const TimedState& a, const TimedState& b) { return a.t < b.t; });
  return states;
}

StepRadius step_radius(Network& network, const std::string& integrator, double t, const Vec& x,
                       double h) {
  auto map = [&](bool held) -> std::optional<Eigen::MatrixXd> {
    if (integrator == "symplectic_euler") return symplectic_step_map(network, t, x, h, held);
    return rk_step_map(network, tableau_by_name(integrator), t, x, h, held);
  };
  StepRadius r;
  const auto full = map(false);
  if (!full) return r;
  r.full = spectral_radius(*full);
  r.friction_held = r.full;
  r.friction_cap = network.friction_cap_energy(x);
  if (r.full > 1.0 + kUnstableGrowth && r.friction_cap > 0.0) {
    const auto held = map(true);
    if (!held) return r;
    r.friction_held = spectral_radius(*held);
  }
  r.smooth = true;
  return r;
}

bool unstable_step(const StepRadius& r, double headroom, bool chatter_counts) {
  if (!r.smooth || r.full <= 1.0 + kUnstableGrowth) return false;
  const bool runaway = r.friction_held > 1.0 + kUnstableGrowth;
  return runaway || chatter_counts || r.friction_cap > headroom;
}

StepLimit predict_step_limit(Network& network, const std::string& integrator,
                             const std::vector<TimedState>& states, double h_min,
                             double h_max) {
  // stable(h, chatter_counts): no sampled state has a mode growing faster than allowed; a
  // mode only stuck friction carries counts where the monitor would see it, or always if
  // chatter_counts.
  double limiting_time = 0.0;
  auto stable = [&](double h, bool chatter_counts) {
    for (const auto& s : states) {
      const StepRadius r = step_radius(network, integrator, s.t, s.x, h);
      if (unstable_step(r, s.energy_headroom, chatter_counts)) {
        limiting_time = s.t;
        return false;
      }
    }
    return true;
  };
  // The smallest unstable step on a grid of ratio 10^0.1 from h_min up, then bisection below
  // it: stability can come back above a window of instability (a stuck friction spring
  // under RK4), and the first window is the one that matters.
  auto first_limit = [&](bool chatter_counts, double& time) -> std::optional<double> {
    const double ratio = std::pow(10.0, 0.1);
    double lo = 0.0;
    for (double h = h_min;; h = std::min(h * ratio, h_max)) {  // the last point is h_max
      if (stable(h, chatter_counts)) {
        if (h >= h_max) break;
        lo = h;
        continue;
      }
      if (lo == 0.0) {
        time = limiting_time;
        return 0.0;  // unstable at every step size tried
      }
      double hi = h;
      time = limiting_time;
      while (hi / lo > 1.001) {
        const double mid = std::sqrt(lo * hi);
        if (stable(mid, chatter_counts)) {
          lo = mid;
        } else {
          hi = mid;
          time = limiting_time;
        }
      }
      return lo;
    }
    return std::nullopt;  // stable up to h_max
  };
  StepLimit limit;
  double chatter_time = 0.0;
  const auto runaway = first_limit(false, limit.limiting_time);
  const auto chatter = first_limit(true, chatter_time);
  limit.unbounded = !runaway.has_value();
  limit.max_step = runaway.value_or(h_max);
  limit.chatter_free_step = chatter.value_or(h_max);
  return limit;
}

}  // namespace stiction::core
