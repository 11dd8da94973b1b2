// Tells the caller how far the run has got (fraction of the duration), about 100 times a run.
#pragma once

#include <algorithm>

#include "core/run_observer.hpp"
#include "core/simulation.hpp"

namespace stiction::core {

class ProgressObserver final : public RunObserver {
 public:
  // `fixed_steps`: the run's length in steps of RunOptions::dt (a variable step reports at
  // the same step counts).
  ProgressObserver(const ProgressCallback& progress, long fixed_steps, double end)
      : progress_(progress), every_(std::max(1L, fixed_steps / 100)), end_(end) {}
  Verdict after_step(const StepTaken& step) override {
    if ((step.k + 1) % every_ == 0) progress_(step.t_now / end_);
    return Verdict::go_on;
  }

 private:
  const ProgressCallback& progress_;
  long every_;
  double end_;
};

}  // namespace stiction::core
