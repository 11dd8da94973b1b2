#include "core/stability.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/integrator.hpp"

namespace stiction::core {
namespace {

// A step is called unstable where it amplifies some mode by more than 5% per step: such
// growth runs away within tens of steps. Weaker growth is left out on purpose: a rolling
// contact linearized about a point of its orbit grows at a few 1/s (physics, not the step),
// and RK4 on the stiff stuck-friction spring of sphere_roll has a window near
// dt = 2.3e-4 s where that mode grows by ~3% per step; friction saturation bounds it (the
// contact slips a little), so runs there stay bounded, as `stiction study` confirms.
constexpr double kUnstableGrowth = 0.05;

}  // namespace

std::vector<TimedState> sample_states(Network& network, const RunOptions& options, int count) {
  auto stepper = make_stepper(options.integrator, network.state_dim(), options.dt,
                              options.tolerance);
  std::vector<TimedState> states;
  Vec x = network.initial_state();
  double t = 0.0;
  const double every = options.duration / std::max(1, count);
  double next = 0.0;
  while (t < options.duration) {
    if (t >= next) {
      states.push_back({t, x});
      next += every;
    }
    t += stepper->advance(network, t, options.duration - t, x);
    if (!x.allFinite()) break;
  }
  return states;
}

double step_spectral_radius(Network& network, const std::string& integrator, double t,
                            const Vec& x, double h) {
  const int n = static_cast<int>(x.size());
  auto stepper = make_stepper(integrator, n, h);
  Eigen::MatrixXd jacobian(n, n);
  Vec center = x, plus(n), minus(n);
  // Linearization holds only if no element switches regime (contact closing, friction
  // sticking) within the step: compare the regimes at the start, middle and end.
  const std::size_t regime = network.regime_signature(x, h);
  Vec half = x;
  make_stepper(integrator, n, h / 2)->advance(network, t, h / 2, half);
  stepper->advance(network, t, h, center);
  if (network.regime_signature(half, h) != regime || network.regime_signature(center, h) != regime) {
    return std::numeric_limits<double>::quiet_NaN();
  }
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
      stepper->advance(network, t, h, plus);
      stepper->advance(network, t, h, minus);
      const Vec forward = (plus - center) / delta;
      const Vec backward = (center - minus) / delta;
      // On a switching surface the one-sided differences disagree.
      const double scale =
          1.0 + forward.lpNorm<Eigen::Infinity>() + backward.lpNorm<Eigen::Infinity>();
      if ((forward - backward).lpNorm<Eigen::Infinity>() <= 1e-4 * scale) {
        jacobian.col(i) = 0.5 * (forward + backward);
        smooth = true;
        break;
      }
    }
    // No Jacobian here: such a state says nothing about linear stability; the caller skips it.
    if (!smooth) return std::numeric_limits<double>::quiet_NaN();
  }
  if (!jacobian.allFinite()) return std::numeric_limits<double>::infinity();
  return Eigen::EigenSolver<Eigen::MatrixXd>(jacobian, false).eigenvalues().cwiseAbs().maxCoeff();
}

StepLimit predict_step_limit(Network& network, const std::string& integrator,
                             const std::vector<TimedState>& states, double h_min,
                             double h_max) {
  double limiting_time = 0.0;
  auto stable = [&](double h) {
    std::size_t smooth = 0;
    for (const auto& s : states) {
      const double radius = step_spectral_radius(network, integrator, s.t, s.x, h);
      if (std::isnan(radius)) continue;  // an element switches regime within the step
      ++smooth;
      if (radius > 1.0 + kUnstableGrowth) {
        limiting_time = s.t;
        return false;
      }
    }
    // A step so long that every state switches regime within it is not predicted stable:
    // the linearization has nothing left to say about it.
    return smooth > 0;
  };
  StepLimit limit;
  if (stable(h_max)) {
    limit.max_step = h_max;
    limit.unbounded = true;
    return limit;
  }
  double time_at_hi = limiting_time;
  if (!stable(h_min)) {
    limit.limiting_time = limiting_time;
    return limit;  // unstable at every step size tried
  }
  double lo = h_min, hi = h_max;
  while (hi / lo > 1.001) {
    const double mid = std::sqrt(lo * hi);
    if (stable(mid)) {
      lo = mid;
    } else {
      hi = mid;
      time_at_hi = limiting_time;
    }
  }
  limit.max_step = lo;
  limit.limiting_time = time_at_hi;
  return limit;
}

}  // namespace stiction::core
