// Ends the run before a step once RunOptions::stop is set (SIGINT, app/interrupt.hpp),
// looking at the flag only every kEvery steps: an atomic load per step would be cheap, not free.
#pragma once

#include <atomic>

#include "core/run_observer.hpp"
#include "core/simulation.hpp"

namespace stiction::core {

class InterruptObserver final : public RunObserver {
 public:
  InterruptObserver(const std::atomic<bool>* stop, RunResult& result)
      : stop_(stop), result_(result) {}
  Before before_step(const StepPlan& plan) override {
    if (stop_ != nullptr && plan.k % kEvery == 0 && stop_->load(std::memory_order_relaxed)) {
      result_.interrupted = true;
      return {Verdict::stop, false};
    }
    return {};
  }

  static constexpr long kEvery = 64;

 private:
  const std::atomic<bool>* stop_;
  RunResult& result_;
};

}  // namespace stiction::core
