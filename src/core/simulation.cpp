#include "core/simulation.hpp"

#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <vector>

#include "core/flush_subnormals.hpp"
#include "core/instability_observer.hpp"
#include "core/interrupt_observer.hpp"
#include "core/model_fault.hpp"
#include "core/progress_observer.hpp"
#include "core/row_sampler.hpp"
#include "core/run_limits.hpp"
#include "core/slip_observer.hpp"
#include "core/integrator_traits.hpp"

namespace stiction::core {

double adaptive_step_bound(const RunOptions& options) {
  return kAdaptiveRowsPerStep / options.output_rate;
}

RunResult simulate(Network& network, const RunOptions& options, const ProgressCallback& progress,
                   RowSink* sink) {
  if (const auto violation = check_run_limits(options)) {
    throw std::invalid_argument(violation->key + ": " + violation->message);
  }
  const FlushSubnormals flush_subnormals;  // a body at rest must not slow the run down
  RunResult result;
  const double T = options.dt;
  const double end = options.duration;
  const bool fixed_step = !is_adaptive(options.integrator);
  const long total_steps = static_cast<long>(std::ceil(end / T - 1e-9));
  auto stepper = make_stepper(options.integrator, network.state_dim(), T, options.tolerance,
                              adaptive_step_bound(options), &network);
  Vec x = network.initial_state();
  Vec x_prev = x;

  // Constructed in this order (each may evaluate the network at x), and called in this
  // order: an instability stops the run before its step is observed or sampled.
  SlipObserver slips(network, options, *stepper, result, x);
  InstabilityObserver instability(network, options, result, x);
  InterruptObserver interrupt(options.stop, result);
  const auto start = std::chrono::steady_clock::now();
  RowSampler rows(network, options, *stepper, result, sink, x);
  std::optional<ProgressObserver> progress_observer;
  if (progress) progress_observer.emplace(progress, total_steps, end);
  std::vector<RunObserver*> observers{&interrupt, &instability, &slips, &rows};
  if (progress_observer) observers.push_back(&*progress_observer);

  double t = 0.0;
  for (long k = 0; t < end; ++k) {
    const double t_next = fixed_step ? ((k + 1 >= total_steps) ? end : (k + 1) * T) : end;
    // The step's start state is copied only when an observer will read it (with 100 bodies
    // the copy is a few percent of the step).
    bool keep_start = !fixed_step;
    bool stop = false;
    for (RunObserver* o : observers) {
      const RunObserver::Before before = o->before_step({k, t, t_next});
      if (before.verdict == Verdict::stop) {
        stop = true;
        break;
      }
      keep_start |= before.reads_start;
    }
    if (stop) break;
    if (keep_start) x_prev = x;
    double h = 0.0;
    try {
      h = stepper->advance(network, t, end - t, x);
    } catch (const std::runtime_error& error) {
      if (dynamic_cast<const ModelFault*>(&error) != nullptr) throw;  // bad input, not a step
      for (RunObserver* o : observers) o->after_advance(x);
      result.instability = Instability{t, "integrator", error.what()};
      break;
    }
    for (RunObserver* o : observers) o->after_advance(x);
    // Fixed steps: time from the step count, so a long run does not accumulate rounding.
    const double t_now = fixed_step ? t_next : t + h;
    result.steps = k + 1;
    result.evaluations = stepper->evaluations();
    const StepTaken step{k, t, t_now, h, x_prev, x};
    for (RunObserver* o : observers) {
      if (o->after_step(step) == Verdict::stop) {
        stop = true;
        break;
      }
    }
    if (stop) break;
    t = t_now;
  }
  for (RunObserver* o : observers) o->finish(x);
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace stiction::core
