#include "core/instability_monitor.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace stiction::core {
namespace {

// The admittance whose energy grew the most over the last step.
std::string fastest_growing(Network& network, const Vec& before, const Vec& after) {
  std::string name = "network";
  double worst = -1.0;
  for (std::size_t j = 0; j < network.admittances().size(); ++j) {
    const Slot s = network.admittance_slot(static_cast<int>(j));
    const auto& a = *network.admittances()[j];
    const double growth = a.energy(after.segment(s.state_offset, s.state_size)) -
                          a.energy(before.segment(s.state_offset, s.state_size));
    if (growth > worst) {
      worst = growth;
      name = a.name();
    }
  }
  return name;
}

}  // namespace

InstabilityMonitor::InstabilityMonitor(Network& network, const RunOptions& options, const Vec& x0)
    : network_(network),
      has_sources_(network.has_sources()),
      power_checked_(has_sources_ ? std::abs(network.source_power(0.0, x0)) : 0.0),
      budget_(network, options.energy_tolerance),
      feedback_(network, options, x0) {
  budget_.observe(x0, 0.0);
  for (std::size_t i = 0; i < network.impedances().size(); ++i) {
    const Impedance& imp = *network.impedances()[i];
    const Slot s = network.impedance_slot(static_cast<int>(i));
    const auto* bound = network.capabilities(static_cast<int>(i)).bound;  // BoundedState
    if (bound == nullptr || !std::isfinite(bound->state_bound()) || s.state_size == 0) continue;
    // Twice the bound (or the initial value, if larger) is past any rounding.
    const double start = x0.segment(s.state_offset, s.state_size).lpNorm<Eigen::Infinity>();
    bounded_.push_back({imp.name(), s, 2.0 * std::max(bound->state_bound(), start)});
  }
}

std::optional<Instability> InstabilityMonitor::check(double t, const Vec& x_prev, const Vec& x) {
  if (has_sources_) {
    const double power = std::abs(network_.source_power(t, x));
    work_in_ += 0.5 * (power_checked_ + power) * (t - t_checked_);
    power_checked_ = power;
    t_checked_ = t;
  }
  budget_.observe(x, work_in_);
  // With feedback sources, their work is neither credited nor charged: FeedbackMonitor.
  if (budget_.overflowed()) {
    return Instability{t, fastest_growing(network_, x_prev, x),
                       "energy is not a finite number (the state overflows)"};
  }
  if (!feedback_.active() && budget_.exceeded()) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "energy grew beyond what the sources put in (by %.3g J, past the tolerance "
                  "%.3g J of the energy scale %.3g J)",
                  budget_.rise(), budget_.allowed(), budget_.scale());
    return Instability{t, fastest_growing(network_, x_prev, x), text};
  }
  if (auto reason = feedback_.check(t, x_prev, x, budget_)) {
    return Instability{t, fastest_growing(network_, x_prev, x), std::move(*reason)};
  }
  for (const auto& b : bounded_) {
    if (x.segment(b.slot.state_offset, b.slot.state_size).lpNorm<Eigen::Infinity>() > b.limit) {
      return Instability{t, b.component, "state past twice the bound its model keeps"};
    }
  }
  return std::nullopt;
}

}  // namespace stiction::core
