#include "core/step_control.hpp"

#include <algorithm>
#include <cmath>

#include "core/capabilities.hpp"

namespace stiction::core {

double StepController::factor(double error) const {
  const double q = static_cast<double>(error_order);
  return std::clamp(safety * std::pow(std::max(error, 1e-10), -1.0 / q), min_factor, max_factor);
}

void set_error_floors(Network& network, const Vec& x, Vec& floor) {
  floor.setOnes(x.size());
  for (int i = 0; i < static_cast<int>(network.impedances().size()); ++i) {
    const Capabilities& c = network.capabilities(i);
    const Slot s = network.impedance_slot(i);
    if (c.friction == nullptr || c.stiffness == nullptr || s.state_size == 0 ||
        !(c.stiffness->stiffness() > 0.0)) {
      continue;
    }
    // friction_cap_energy = F^2 / K.
    const double cap = c.friction->friction_cap_energy(network.impedance_input(i, x));
    const double size = std::sqrt(cap / c.stiffness->stiffness());
    if (size > 0.0 && size < 1.0) floor.segment(s.state_offset, s.state_size).setConstant(size);
  }
}

double scaled_error(const Vec& difference, const Vec& x, const Vec& floor, double tolerance,
                    double divisor) {
  double worst = 0.0;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    const double scale = tolerance * (floor[i] + std::abs(x[i]));
    worst = std::max(worst, std::abs(difference[i]) / (divisor * scale));
  }
  return std::isfinite(worst) ? worst : 1e10;
}

bool same_regimes(Network& network, const Vec& a, std::size_t a_regimes, const Vec& b, double tau,
                  const Island* part) {
  if (network.regime_signature(b, tau, part) != a_regimes) return false;
  // A clamping friction element sliding at both ends whose slip reversed passed through
  // zero, where its friction holds: a switch there and back within the step. (A stuck
  // element's spring vibrating reverses all the time; that is no switch.)
  const int count = part != nullptr ? static_cast<int>(part->impedances.size())
                                    : static_cast<int>(network.impedances().size());
  for (int k = 0; k < count; ++k) {
    const int i = part != nullptr ? part->impedances[static_cast<std::size_t>(k)] : k;
    const Capabilities& c = network.capabilities(i);
    if (c.slip == nullptr || c.friction == nullptr) continue;
    const Slot s = network.impedance_slot(i);
    const Vec3 before = c.slip->slip_velocity(network.impedance_input(i, a));
    if (c.friction->regime(network.impedance_input(i, a), a.segment(s.state_offset, s.state_size),
                           tau) != 2) {
      continue;
    }
    if (c.slip->slip_velocity(network.impedance_input(i, b)).dot(before) < 0.0) return false;
  }
  return true;
}

double locate_switch(Network& network, double t, double h, const Vec& x, std::size_t start_regimes,
                     double tau, const std::function<bool(double, Vec&)>& take_step, Vec& probe,
                     const Island* part) {
  const double precision = std::max(kSwitchPrecision * h, 1e-13 * std::max(1.0, std::abs(t)));
  double lo = 0.0, hi = h;
  while (hi - lo > precision) {
    const double mid = 0.5 * (lo + hi);
    if (part != nullptr) {
      for (int e : part->states) probe[e] = x[e];
    } else {
      probe = x;
    }
    if (take_step(mid, probe) && same_regimes(network, x, start_regimes, probe, tau, part)) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return lo > 0.0 ? lo : hi;  // land just before the switch, or cross it if it is at t
}

double min_adaptive_step(double t) { return 1e-14 * std::max(1.0, std::abs(t)); }

}  // namespace stiction::core
