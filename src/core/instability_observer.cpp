#include "core/instability_observer.hpp"

namespace stiction::core {
namespace {

// The component owning the first non-finite state slot.
std::string owner_of_non_finite(Network& network, const Vec& x) {
  for (const auto& entry : network.layout()) {
    if (!x.segment(entry.offset, entry.size).allFinite()) return entry.component;
  }
  return "(unknown)";
}

}  // namespace

InstabilityObserver::InstabilityObserver(Network& network, const RunOptions& options,
                                         RunResult& result, const Vec& x0)
    : network_(network), result_(result), monitor_(network, options, x0), end_(options.duration) {}

RunObserver::Before InstabilityObserver::before_step(const StepPlan& plan) {
  return {Verdict::go_on, due(plan.k, plan.t_next)};  // the monitor compares with the start
}

Verdict InstabilityObserver::after_step(const StepTaken& step) {
  if (!step.x.allFinite()) {
    result_.instability =
        Instability{step.t_now, owner_of_non_finite(network_, step.x), "state is not finite"};
    return Verdict::stop;
  }
  if (due(step.k, step.t_now)) {
    if (auto found = monitor_.check(step.t_now, step.x_prev, step.x)) {
      result_.instability = std::move(found);
      return Verdict::stop;
    }
  }
  return Verdict::go_on;
}

}  // namespace stiction::core
