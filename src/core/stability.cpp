#include "core/stability.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "core/integrator.hpp"

namespace stiction::core {
namespace {

// Spectral radii a little above 1 come from the neutral modes (free translation and
// rotation, whose step Jacobians are Jordan blocks at 1) and from rounding.
constexpr double kNeutralSlack = 1e-6;

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
  Vec plus(n), minus(n);
  for (int i = 0; i < n; ++i) {
    const double delta = 1e-7 * std::max(std::abs(x[i]), 1e-3);
    plus = x;
    plus[i] += delta;
    minus = x;
    minus[i] -= delta;
    stepper->advance(network, t, h, plus);
    stepper->advance(network, t, h, minus);
    jacobian.col(i) = (plus - minus) / (2.0 * delta);
  }
  if (!jacobian.allFinite()) return std::numeric_limits<double>::infinity();
  return Eigen::EigenSolver<Eigen::MatrixXd>(jacobian, false).eigenvalues().cwiseAbs().maxCoeff();
}

StepLimit predict_step_limit(Network& network, const std::string& integrator,
                             const std::vector<TimedState>& states, double h_min,
                             double h_max) {
  double limiting_time = 0.0;
  auto stable = [&](double h) {
    for (const auto& s : states) {
      if (step_spectral_radius(network, integrator, s.t, s.x, h) > 1.0 + kNeutralSlack) {
        limiting_time = s.t;
        return false;
      }
    }
    return true;
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
