// Stops the run at the first sign of numerical instability: at once on a non-finite state
// (naming the component that owns it), and every kMonitorEvery steps (and at the last) when
// the InstabilityMonitor (core/instability_monitor.hpp) sees the energy or a bounded state
// run away. A numerical instability grows geometrically, so a short delay in noticing it
// costs nothing, while checking every step would.
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

  static constexpr long kMonitorEvery = 8;  // steps between two checks of the monitor

 private:
  bool due(long k, double t_now) const { return (k + 1) % kMonitorEvery == 0 || t_now >= end_; }

  Network& network_;
  RunResult& result_;
  InstabilityMonitor monitor_;
  double end_;
};

}  // namespace stiction::core
