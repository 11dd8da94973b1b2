// Ends the run before a step once RunOptions::stop is set (SIGINT, app/interrupt.hpp).
// The flag is looked at before every step: a relaxed load is a plain read, and a step can be
// slow (an adaptive step of 2016 pair contacts took 9 ms in Release, 0.3-0.7 s under the
// sanitizers), so looking only every 64th step let a stop wait 20-50 s (fuzz_pairs' timeout).
#pragma once

#include <atomic>

#include "core/run_observer.hpp"
#include "core/simulation.hpp"

namespace stiction::core {

class InterruptObserver final : public RunObserver {
 public:
  InterruptObserver(const std::atomic<bool>* stop, RunResult& result)
      : stop_(stop), result_(result) {}
  Before before_step(const StepPlan& /*plan*/) override {
    if (stop_ != nullptr && stop_->load(std::memory_order_relaxed)) {
      result_.interrupted = true;
      return {Verdict::stop, false};
    }
    return {};
  }

 private:
  const std::atomic<bool>* stop_;
  RunResult& result_;
};

}  // namespace stiction::core
