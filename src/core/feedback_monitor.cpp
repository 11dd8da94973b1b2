#include "core/feedback_monitor.hpp"

#include <cmath>
#include <cstdio>

#include "core/integrator_traits.hpp"

namespace stiction::core {

FeedbackMonitor::FeedbackMonitor(Network& network, const RunOptions& options, const Vec& x0)
    : network_(network),
      options_(options),
      active_(network.has_feedback_sources() && !is_adaptive(options.integrator) &&
              std::isfinite(network.energy(x0))),
      driven_(network, options.energy_tolerance) {
  if (!active_) return;
  driven_.observe(x0, 0.0);
  power_checked_ = std::abs(network.source_power(0.0, x0, true));
  x_checked_ = x0;
}

StepRadius FeedbackMonitor::radius(double t, const Vec& x_prev, const Vec& x) {
  const std::string& integrator = options_.integrator;
  const double h = options_.dt;
  StepRadius r = step_radius(network_, integrator, t, x, h);
  if (r.smooth) return r;
  // x_prev's time is taken a whole step back (the last step of a run may be shorter).
  r = step_radius(network_, integrator, t - h, x_prev, h);
  if (r.smooth) return r;
  if (!replay_) replay_ = make_stepper(integrator, network_.state_dim(), h, options_.tolerance);
  Vec y = x_checked_;
  for (double s = t_checked_; s < t && y.allFinite();) {
    s += replay_->advance(network_, s, t - s, y);
    r = step_radius(network_, integrator, s, y, h);
    if (r.smooth) return r;
  }
  return r;
}

std::optional<std::string> FeedbackMonitor::check(double t, const Vec& x_prev, const Vec& x,
                                                  const EnergyBudget& all_sources) {
  if (!active_) return std::nullopt;
  const double power = std::abs(network_.source_power(t, x, true));
  driven_work_ += 0.5 * (power_checked_ + power) * (t - t_checked_);
  power_checked_ = power;
  std::optional<std::string> unstable;
  driven_.observe(x, driven_work_);
  // Growth past what the time-driven sources allow: the feedback's work, or the integrator.
  const double excess = driven_.rise() - driven_.allowed();
  if (driven_.monitored() && excess > 0.0 && excess > 2.0 * verified_excess_) {
    const StepRadius r = radius(t, x_prev, x);
    if (unstable_step(r, all_sources.headroom())) {
      char text[240];
      std::snprintf(text, sizeof text,
                    "energy grew beyond what the time-driven sources put in, and the step map "
                    "linearized there amplifies a mode %.3g-fold per step (a feedback source's "
                    "work is not taken as put in from outside)",
                    r.full);
      unstable = text;
    } else if (r.smooth) {
      verified_excess_ = excess;
    }  // else no answer anywhere: asked again at the next check
  }
  t_checked_ = t;
  x_checked_ = x;
  return unstable;
}

}  // namespace stiction::core
