#include "services/run_support.hpp"

#include <algorithm>
#include <cstdio>
#include <memory>

#include <unistd.h>

#include "services/pilot.hpp"
#include "services/progress.hpp"
#include "core/integrator_traits.hpp"
#include "core/run_limits.hpp"
#include "core/stability.hpp"
#include "text/number_text.hpp"

namespace stiction::services {

io::RunDescription describe_run(const scene::Scene& scene) {
  io::RunDescription d;
  d.scene = scene.name;
  d.integrator = scene.run.integrator;
  d.dt = scene.run.dt;
  d.duration = scene.run.duration;
  d.output_rate = scene.run.output_rate;
  d.state_dim = scene.network->state_dim();
  if (scene.run.tolerance > 0.0) d.tolerance = scene.run.tolerance;
  return d;
}

namespace {
std::string adaptive_names() {
  std::string names;
  for (const std::string& n : core::adaptive_integrator_names()) names += (names.empty() ? "" : ", ") + n;
  return names;
}
}  // namespace

void apply_overrides(scene::Scene& scene, const RunOverrides& overrides) {
  core::RunOptions& run = scene.run;
  if (overrides.tolerance) {
    // --tolerance runs the adaptive integrator that --integrator names, else the scene's if
    // it is adaptive, else the default one (rk4_adaptive).
    if (overrides.integrator && !core::is_adaptive(*overrides.integrator)) {
      throw scene::InputError("error: --tolerance selects an adaptive integrator (" +
                              adaptive_names() +
                              "); it cannot be combined with --integrator " + *overrides.integrator);
    }
    if (overrides.integrator) {
      run.integrator = *overrides.integrator;
    } else if (!core::is_adaptive(run.integrator)) {
      run.integrator = core::adaptive_integrator().name;
    }
    run.tolerance = *overrides.tolerance;
  } else if (overrides.integrator) {
    run.integrator = *overrides.integrator;
  }
  if (overrides.dt) run.dt = *overrides.dt;
  if (overrides.duration) run.duration = *overrides.duration;
  if (core::is_adaptive(run.integrator) && !(run.tolerance > 0.0)) {
    throw scene::InputError("error: --integrator " + run.integrator +
                            " needs a tolerance: give --tolerance TOL or set [simulation] tolerance "
                            "in the scene");
  }
  // The scene's own values were checked where they were read; what fails here comes from the
  // command line (or from it combined with the scene).
  if (const auto violation = core::check_user_run(run)) {
    throw scene::InputError("error: " + scene.path.string() + " with --dt/--duration/--tolerance: simulation." +
                            violation->key + ": " + violation->message);
  }
}

// A bar on a terminal, plain lines in a log (ProgressBar decides); nothing with --quiet.
bool show_progress(bool quiet) { return !quiet; }

core::RunResult simulate_scene(scene::Scene& scene, bool progress, core::RowSink* sink) {
  std::unique_ptr<ProgressBar> bar;
  core::ProgressCallback callback;
  if (progress) {
    bar = std::make_unique<ProgressBar>("simulate " + scene.name);
    const double duration = scene.run.duration;
    callback = [&bar, duration](double fraction) { bar->simulation(fraction, duration); };
  }
  core::RunResult result = core::simulate(*scene.network, scene.run, callback, sink);
  if (bar) bar->finish(result.instability ? "unstable" : std::to_string(result.steps) + " steps");
  return result;
}

std::map<std::string, double> event_times(const core::RunResult& result) {
  std::map<std::string, double> events;
  for (const core::SlipHistory& h : result.slip_events) {
    const double t = h.monitor.stick_time();
    if (t >= 0.0) events[h.component + ".stick_time"] = t;
    const double slip = h.monitor.first_slip();
    if (slip >= 0.0) events[h.component + ".slip_time"] = slip;  // labelled "<element> slip"
  }
  return events;
}

StepSuggestion suggested_dt(scene::Scene& scene, const StepCheck& check) {
  return suggest_step(scene, check);
}

void print_instability(const std::string& scene_name, const core::RunOptions& run,
                       const core::Instability& inst, const StepSuggestion& suggestion) {
  if (core::is_adaptive(run.integrator)) {
    // The step shrank to nothing without meeting the tolerance: it is below what rounding
    // lets the state show, and a smaller one would only fail sooner (issue 39).
    const bool underflow = inst.reason.find("underflow") != std::string::npos;
    std::fprintf(stderr,
                 "error: %s: numerical instability at t = %.6g s in '%s' (%s) with %s, "
                 "tolerance %s; %s, e.g. --tolerance %g\n",
                 scene_name.c_str(), inst.time, inst.component.c_str(), inst.reason.c_str(),
                 run.integrator.c_str(), text::shortest(run.tolerance).c_str(),
                 underflow ? "no step met that tolerance in double precision: try a larger one"
                           : "try a smaller tolerance",
                 underflow ? std::max(100.0 * run.tolerance, 1e-10) : run.tolerance / 10.0);
    return;
  }
  std::fprintf(stderr,
               "error: %s: numerical instability at t = %.6g s in '%s' (%s) with %s, dt = %s s; "
               "try a smaller step, e.g. --dt %g\n  (that step is %s)\n",
               scene_name.c_str(), inst.time, inst.component.c_str(), inst.reason.c_str(),
               run.integrator.c_str(), text::shortest(run.dt).c_str(), suggestion.dt,
               suggestion.how.c_str());
}

}  // namespace stiction::services
