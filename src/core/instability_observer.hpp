// Stops the run at the first sign of numerical instability: at once on a non-finite state
// (naming the component that owns it), and every kMonitorEvery steps (and at the last) when
// the InstabilityMonitor (core/instability_monitor.hpp) sees the energy rise beyond what the
// sources put in, or a bounded state run away.
#pragma once

#include "core/instability_monitor.hpp"
#include "core/run_observer.hpp"

namespace stiction::core {

class InstabilityObserver final : public RunObserver {
 public:
  InstabilityObserver(Network& network, const RunOptions& options, RunResult& result,
                      const Vec& x0);
  Before before_step(const StepPlan& plan) override;
  Verdict after_step(const StepTaken& step) override;

  // Steps between two checks of the monitor: every step, since the energy monitor must see a
  // rise of 1% of the energy scale that lasts a few steps (issue 26; about 13% of box_slope's
  // CPU time under rk4).
  static constexpr long kMonitorEvery = 1;

 private:
  bool due(long k, double t_now) const { return (k + 1) % kMonitorEvery == 0 || t_now >= end_; }

  Network& network_;
  RunResult& result_;
  InstabilityMonitor monitor_;
  double end_;
};

}  // namespace stiction::core
