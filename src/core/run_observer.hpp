// What core::simulate calls around each step, as Drake's Simulator calls its monitors and
// Odeint its observers: the loop owns time and the state, each observer one concern (rows,
// slip events, instability, interrupts, progress). Hooks run in the order the observers were
// listed, every step, so keep them cheap: the loop's cost is their sum.
#pragma once

#include "core/types.hpp"

namespace stiction::core {

// The step about to be taken: step k (0-based) from t; a fixed step ends at t_next, a
// variable one at most there (the run's end).
struct StepPlan {
  long k;
  double t;
  double t_next;
};

// The step just taken, from (t, x_prev) to (t_now, x) with the stepper's step h. x_prev is
// the start state only if some observer asked for it in before_step (the copy costs).
struct StepTaken {
  long k;
  double t;
  double t_now;
  double h;
  const Vec& x_prev;
  const Vec& x;
};

enum class Verdict { go_on, stop };

class RunObserver {
 public:
  virtual ~RunObserver() = default;
  // Before the stepper runs: stop (the run ends interrupted), or go on and say whether this
  // observer will read the step's start state in after_step.
  struct Before {
    Verdict verdict = Verdict::go_on;
    bool reads_start = false;
  };
  virtual Before before_step(const StepPlan&) { return {}; }
  // Right after the stepper returned, or threw (x then is the step's start state): before
  // anything judges the state.
  virtual void after_advance(const Vec&) {}
  // After the step; stop ends the run (the observer says why in the result) and the later
  // observers do not see this step. The interrupt observer comes first, then the instability
  // observer, so the others see finite states only.
  virtual Verdict after_step(const StepTaken&) { return Verdict::go_on; }
  // Once, at the state the run ends at (also after an instability or an interrupt).
  virtual void finish(const Vec&) {}
};

}  // namespace stiction::core
