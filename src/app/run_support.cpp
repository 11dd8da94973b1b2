#include "app/run_support.hpp"

#include <cstdio>
#include <memory>

#include <unistd.h>

#include "app/progress.hpp"
#include "core/stability.hpp"

namespace stiction::app {
namespace {

// The flag a SIGINT handler may touch must be reachable without arguments; it is set only
// while an InterruptFlag lives. A lock-free atomic pointer is safe to read in a handler.
std::atomic<std::atomic<bool>*> interrupt_target{nullptr};
static_assert(std::atomic<std::atomic<bool>*>::is_always_lock_free);
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void on_interrupt(int) {
  if (std::atomic<bool>* flag = interrupt_target.load()) flag->store(true);
}

}  // namespace

void apply_overrides(scene::Scene& scene, const RunOverrides& overrides) {
  core::RunOptions& run = scene.run;
  if (overrides.tolerance) {
    if (overrides.integrator && *overrides.integrator != "rk4_adaptive") {
      throw scene::InputError("error: --tolerance selects the integrator rk4_adaptive; it cannot be "
                              "combined with --integrator " + *overrides.integrator);
    }
    run.integrator = "rk4_adaptive";
    run.tolerance = *overrides.tolerance;
  } else if (overrides.integrator) {
    run.integrator = *overrides.integrator;
  }
  if (overrides.dt) run.dt = *overrides.dt;
  if (overrides.duration) run.duration = *overrides.duration;
  if (run.integrator == "rk4_adaptive" && !(run.tolerance > 0.0)) {
    throw scene::InputError("error: --integrator rk4_adaptive needs a tolerance: give --tolerance "
                            "TOL or set [simulation] tolerance in the scene");
  }
}

bool show_progress(bool quiet) { return !quiet && ::isatty(STDERR_FILENO) == 1; }

core::RunResult simulate_scene(scene::Scene& scene, bool progress, core::RowSink* sink) {
  std::unique_ptr<ProgressBar> bar;
  core::ProgressCallback callback;
  if (progress) {
    bar = std::make_unique<ProgressBar>("simulate " + scene.name);
    const double duration = scene.run.duration;
    callback = [&bar, duration](double fraction) { bar->simulation(fraction, duration); };
  }
  return core::simulate(*scene.network, scene.run, callback, sink);
}

std::map<std::string, double> event_times(const core::RunResult& result) {
  std::map<std::string, double> events;
  for (const core::SlipHistory& h : result.slip_events) {
    const double t = h.monitor.stick_time();
    if (t >= 0.0) events[h.component + ".stick_time"] = t;
  }
  return events;
}

double suggested_dt(scene::Scene& scene) {
  const core::RunOptions& run = scene.run;
  const double quarter = run.dt / 4.0;
  if (run.integrator == "rk4_adaptive") return quarter;  // its tolerance is what to change
  core::RunOptions pilot = run;
  pilot.dt = quarter;
  const auto states = core::sample_states(*scene.network, pilot, 10);
  const core::StepLimit limit =
      core::predict_step_limit(*scene.network, run.integrator, states, 1e-9, run.dt);
  if (!limit.unbounded && limit.max_step > 0.0 && 0.8 * limit.max_step < run.dt) {
    return 0.8 * limit.max_step;
  }
  // The linearization sees nothing wrong at this step (a non-linear or impact-driven
  // instability): fall back to a quarter of the step.
  return quarter;
}

void print_instability(const std::string& scene_name, const core::RunOptions& run,
                       const core::Instability& inst, double suggested_dt) {
  if (run.integrator == "rk4_adaptive") {
    std::fprintf(stderr,
                 "error: %s: numerical instability at t = %.6g s in '%s' (%s) with rk4_adaptive, "
                 "tolerance %g; try a smaller tolerance, e.g. --tolerance %g\n",
                 scene_name.c_str(), inst.time, inst.component.c_str(), inst.reason.c_str(),
                 run.tolerance, run.tolerance / 10.0);
    return;
  }
  std::fprintf(stderr,
               "error: %s: numerical instability at t = %.6g s in '%s' (%s) with %s, dt = %g s; "
               "try a smaller step, e.g. --dt %g\n",
               scene_name.c_str(), inst.time, inst.component.c_str(), inst.reason.c_str(),
               run.integrator.c_str(), run.dt, suggested_dt);
}

InterruptFlag::InterruptFlag(std::atomic<bool>& flag) {
  interrupt_target.store(&flag);
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;  // a second Ctrl-C ends the process at once
  installed_ = ::sigaction(SIGINT, &action, &previous_) == 0;
}

InterruptFlag::~InterruptFlag() {
  if (installed_) ::sigaction(SIGINT, &previous_, nullptr);
  interrupt_target.store(nullptr);
}

}  // namespace stiction::app
