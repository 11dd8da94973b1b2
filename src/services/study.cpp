#include "services/study.hpp"

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>

#include "core/integrator.hpp"
#include "core/integrator_traits.hpp"
#include "scene/scene.hpp"
#include "services/accuracy.hpp"
#include "services/study_grid.hpp"
#include "services/study_limits.hpp"
#include "services/study_reference.hpp"
#include "sys/interrupt.hpp"

// The study's course: the reference (study_reference.hpp), the predicted limits, the grids of
// each integrator, the two bisections (study_limits.hpp), the candidates
// (study_recommendation.cpp) and the recommendation confirmed as `run` judges it.
namespace stiction::services {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Rows whose key error is above this (relative to the signals' scale) have left the
// asymptotic range: the method is stable but the answer is qualitatively wrong.
constexpr double kSaturatedError = 0.05;
// Rows within this factor of the reference's noise are measuring the reference.
constexpr double kNoiseFactor = 10.0;

std::string format_g(double value, int digits = 3) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  if (n == 0) return kNaN;
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

bool is_fixed_step(const std::string& integrator) { return !core::is_adaptive(integrator); }

// CPU time of this thread: core::simulate runs in the calling thread, so this is the
// simulation's own CPU time, whatever else the process does (the heartbeat thread).
double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

class Study {
 public:
  Study(const StudyOptions& options, const StudyLog& log)
      : options_(options),
        log_(log),
        scene_(scene::load_scene(options.scene, options.overrides)),
        reference_(scene_, options.target_error, result_),
        limits_(options, result_,
                [this](const std::string& integrator, double h) { return probe(integrator, h); },
                log) {
    result_.scene = scene_.name;
    result_.scene_dt = scene_.run.dt;
    result_.duration = scene_.run.duration;
    result_.output_rate = scene_.run.output_rate;
    result_.reference_dt = options.reference_dt.value_or(scene_.run.dt / 16.0);
    if (!(result_.reference_dt > 0.0)) throw scene::InputError("--reference-dt: must be > 0");
    integrators_ = options.integrators.empty() ? core::integrator_names() : options.integrators;
    for (const auto& name : integrators_) {
      if (core::find_integrator(name) == nullptr) {
        core::make_stepper(name, 1, 1.0, 1.0);  // throws, naming the known integrators
      }
    }
    for (double dt : options.dts) {
      if (!(dt > 0.0)) throw scene::InputError("--dts: every step must be > 0");
    }
    for (double tol : options.tolerances) {
      if (!(tol > 0.0)) throw scene::InputError("--tolerances: every tolerance must be > 0");
    }
    // A relative error of 1 or more is met by any answer of the right order of magnitude
    // (and by a value of 0 for a signal of any scale): no target at all.
    if (!(options.target_error > 0.0 && options.target_error < 1.0)) {
      throw scene::InputError("--target-error: must be > 0 and < 1 (a relative error), got " +
                              format_g(options.target_error));
    }
    result_.target_error = options.target_error;
  }

  StudyResult run() {
    const auto start = std::chrono::steady_clock::now();
    run_reference();
    const bool any_fixed = std::any_of(integrators_.begin(), integrators_.end(), is_fixed_step);
    if (any_fixed && (options_.dts.empty() || options_.bisect)) limits_.predict(scene_, integrators_);
    for (const auto& integrator : integrators_) {
      if (is_fixed_step(integrator)) {
        run_fixed_grid(integrator);
      } else {
        run_adaptive_grid(integrator);
      }
    }
    for (const auto& integrator : integrators_) {
      if (is_fixed_step(integrator)) result_.orders.push_back(observed_order(result_, integrator));
    }
    if (options_.bisect) {
      for (auto& limit : result_.limits) {
        limits_.bisect_stable(limit, scene_.run.dt);
        limits_.bisect_accurate(limit);
        say("largest step " + limit.integrator + ": stable " + format_g(limit.bisected, 4) +
            " s (" + std::to_string(limit.runs) + " runs), within the target " +
            format_g(limit.accurate, 4) + " s (" + std::to_string(limit.accuracy_runs) +
            " more runs); " +
            (limit.predicted_skipped ? std::string("no prediction (too many states)")
                                     : "predicted unstable above " + format_g(limit.predicted, 4) + " s"));
      }
    } else {
      result_.limits.clear();  // predicted only for the grid: the table is the bisections'
    }
    result_.candidates = recommendation_candidates(result_);
    for (auto& candidate : result_.candidates) retime(candidate);
    result_.recommendation = cheapest(result_.candidates);
    confirm_recommendation(result_.recommendation);
    result_.total_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return std::move(result_);
  }

 private:
  void say(const std::string& line) const {
    if (log_) log_(line);
  }

  void note(const std::string& text) {
    result_.notes.push_back(text);
    say(text);
  }

  core::RunOptions options_for(const std::string& integrator, double dt, double tolerance) const {
    // Every run of the study starts here: an interrupt stops the current run (stop) and the
    // study before the next one (main turns sys::Interrupted into exit 130 / 143).
    if (sys::interrupted()) throw sys::Interrupted{};
    core::RunOptions run = scene_.run;
    run.stop = &sys::interrupt_flag();
    run.integrator = integrator;
    run.dt = dt;
    run.tolerance = tolerance;
    return run;
  }

  void run_reference() {
    const double h = result_.reference_dt;
    const std::string& rk4 = result_.reference_integrator;
    say("reference: " + rk4 + ", dt = " + format_g(h) + " s ...");
    reference_.run(options_for(rk4, h, 0.0), options_for(rk4, 2.0 * h, 0.0));
    std::string line = "reference: " + std::to_string(result_.reference_steps) + " steps in " +
                       format_g(result_.reference_wall_seconds) + " s; rk4 at 2x its step differs by " +
                       format_g(result_.reference_noise) + " (key error)";
    if (reference_.event_count() > 0) {
      line += std::isnan(result_.reference_event_noise)
                  ? ", events not measured (unstable)"
                  : ", " + format_g(result_.reference_event_noise) + " (event times, relative)";
    }
    say(line);
    // A target within 10x of the reference's own error would measure the reference.
    if (!(options_.target_error >= kNoiseFactor * result_.reference_accuracy_noise)) {
      note("--target-error " + format_g(options_.target_error) +
           " is not 10x above the reference's own accuracy error (" +
           format_g(result_.reference_accuracy_noise) +
           ", rk4 at twice its step): runs near the target are judged by the reference's error "
           "as much as their own; pass a smaller --reference-dt");
    }
  }

  // A whole run at step h for the bisections (study_limits.hpp), measured against the target.
  StudyProbe probe(const std::string& integrator, double h) {
    StudyProbe p;
    const core::RunResult run = simulate_timed(options_for(integrator, h, 0.0), p.cpu_seconds);
    p.evaluations = run.evaluations;
    p.stable = !run.instability;
    if (p.stable) {
      const StudyAccuracy a = reference_.accuracy(run);
      p.event_time_error = a.event_time_error;
      p.final_value_error = a.final_value_error;
      p.meets_target = a.meets;
      if (!p.meets_target) p.failure = a.worst_name;
    } else {
      p.failure = "unstable";
    }
    return p;
  }

  StabilityLimit& limit_of(const std::string& integrator) {
    for (auto& limit : result_.limits) {
      if (limit.integrator == integrator) return limit;
    }
    throw std::logic_error("study: no predicted limit for " + integrator);
  }

  // The recommendation must hold as `run` judges it, with a margin from the instability
  // limit: its step is at most kStableMargin x the bisected stable step, and a run at it
  // with `run`'s accuracy companion (accuracy.hpp: half the step, the same comparison) must
  // be accurate; else the step shrinks by kShrink and is tried again (a few times).
  static constexpr double kStableMargin = 0.8;
  static constexpr double kShrink = 0.8;
  void confirm_recommendation(Recommendation& r) {
    if (r.integrator.empty()) return;
    const bool fixed = is_fixed_step(r.integrator);
    if (fixed) {
      for (const StabilityLimit& limit : result_.limits) {
        if (limit.integrator == r.integrator && limit.bisected > 0.0 &&
            r.dt > kStableMargin * limit.bisected && limit.unstable_above > 0.0) {
          r.dt = kStableMargin * limit.bisected;
          r.note = "kept 0.8 x below the largest stable step";
        }
      }
    }
    const core::RunOptions scene_run = scene_.run;
    for (int attempt = 0; attempt < 4; ++attempt) {
      scene_.run = options_for(r.integrator, r.dt, r.tolerance);
      const core::RunResult run = core::simulate(*scene_.network, scene_.run);
      if (!run.instability) {
        AccuracySettings on;
        on.mode = AccuracyMode::on;
        on.rule = reference_.rule();  // at the study's target, as the rows were judged
        on.rule->event_tolerance = on.rule->final_tolerance = options_.target_error;
        const AccuracyEstimate e = estimate_accuracy(scene_, run, {}, on);
        const StudyAccuracy a = reference_.accuracy(run);
        r.run_verdict = e.verdict;
        if (e.verdict == "accurate" && a.meets) {
          scene_.run = scene_run;
          if (!r.note.empty()) {
            r.event_time_error = a.event_time_error;
            r.final_value_error = a.final_value_error;
            r.evaluations_per_second = static_cast<double>(run.evaluations) / result_.duration;
            retime(r);
          }
          say("recommendation confirmed: `run` calls it accurate");
          return;
        }
      } else {
        r.run_verdict = "unstable";
      }
      if (fixed) {
        r.dt *= kShrink;
      } else {
        r.tolerance *= 0.1;
      }
      r.note = "shrunk until `run` calls it accurate";
    }
    scene_.run = scene_run;
    say("the recommendation could not be confirmed by run's accuracy verdict");
  }

  // Times a candidate again like a grid row (median of the repeats within the repeat budget),
  // so that a bisection's single run and a grid row's median compare alike.
  void retime(Recommendation& candidate) {
    const core::RunOptions run =
        options_for(candidate.integrator, candidate.dt, candidate.tolerance);
    std::vector<double> cpus;
    double spent = 0.0;
    while (static_cast<int>(cpus.size()) < std::max(options_.repeats, 1) &&
           (cpus.empty() || spent < options_.repeat_budget_seconds)) {
      double cpu = 0.0;
      spent += simulate_timed(run, cpu).wall_seconds;
      cpus.push_back(cpu);
    }
    candidate.cpu_per_second = median(cpus) / result_.duration;
    candidate.repeats = static_cast<int>(cpus.size());
    say("candidate " + candidate.integrator + " " +
        (candidate.tolerance > 0.0 ? "tol " + format_g(candidate.tolerance)
                                   : "dt " + format_g(candidate.dt)) +
        ": " + format_g(candidate.cpu_per_second) + " CPU s per simulated second (" +
        std::to_string(candidate.repeats) + " runs)");
  }

  // A whole run: the result and the CPU time it took.
  core::RunResult simulate_timed(const core::RunOptions& run, double& cpu_seconds) {
    const double cpu0 = thread_cpu_seconds();
    core::RunResult result = core::simulate(*scene_.network, run);
    cpu_seconds = thread_cpu_seconds() - cpu0;
    return result;
  }

  // One grid point: a first run, then repeats for the timing if they are cheap.
  StudyRow run_point(const std::string& integrator, double dt, double tolerance) {
    const core::RunOptions run = options_for(integrator, dt, tolerance);
    double first_cpu = 0.0;
    core::RunResult first = simulate_timed(run, first_cpu);
    StudyRow row;
    row.integrator = integrator;
    row.dt = dt;
    row.tolerance = tolerance;
    row.steps = first.steps;
    row.evaluations = first.evaluations;
    std::vector<double> walls{first.wall_seconds}, cpus{first_cpu};
    if (first.instability) {
      row.status = "unstable";
      row.instability = first.instability;
    } else {
      row.status = "ok";
      const int extra = static_cast<int>(std::clamp(
          std::floor(options_.repeat_budget_seconds / std::max(first.wall_seconds, 1e-9)) - 1.0,
          0.0, static_cast<double>(std::max(options_.repeats, 1) - 1)));
      for (int i = 0; i < extra; ++i) {
        double cpu = 0.0;
        walls.push_back(simulate_timed(run, cpu).wall_seconds);
        cpus.push_back(cpu);
      }
    }
    row.repeats = static_cast<int>(walls.size());
    row.wall_seconds = median(walls);
    row.cpu_seconds = median(cpus);

    const StudyMeasurement m = reference_.measure(first);
    const std::size_t events = reference_.event_count();
    if (first.instability) {
      row.signal_errors.assign(result_.key_signals.size(), kNaN);
      row.key_error = kNaN;
      row.event_times.assign(events, kNaN);
      row.event_errors.assign(events, kNaN);
      row.event_relative_errors.assign(events, kNaN);
      row.max_event_relative_error = kNaN;
      row.event_time_error = row.final_value_error = kNaN;
      row.meets_target = false;
      row.accuracy_failure = "unstable";
    } else {
      row.signal_errors = reference_.signal_errors(m, is_fixed_step(integrator) ? dt : 0.0);
      std::tie(row.key_error, row.worst_signal) = reference_.key_error(row.signal_errors);
      row.event_times = m.event_times;
      row.max_event_relative_error = events == 0 ? kNaN : 0.0;
      for (std::size_t i = 0; i < events; ++i) {
        const double ref = reference_.event_time(i);
        const double err = std::abs(m.event_times[i] - ref);
        row.event_errors.push_back(err);
        row.event_relative_errors.push_back(err / std::abs(ref));
        // A missing event (NaN) makes the row's event error NaN: it missed the event.
        if (!(row.event_relative_errors.back() <= row.max_event_relative_error)) {
          row.max_event_relative_error = row.event_relative_errors.back();
        }
      }
      const StudyAccuracy a = reference_.accuracy(first);
      row.event_time_error = a.event_time_error;
      row.final_value_error = a.final_value_error;
      row.meets_target = a.meets;
      if (!row.meets_target) row.accuracy_failure = a.worst_name;
    }

    std::string line = integrator + (tolerance > 0.0 ? " tol " + format_g(tolerance)
                                                     : " dt " + format_g(dt)) + ": ";
    if (row.instability) {
      line += "unstable at t = " + format_g(row.instability->time) + " s in '" +
              row.instability->component + "'";
    } else {
      line += format_g(row.wall_seconds) + " s, key error " + format_g(row.key_error) +
              (row.meets_target ? ", within the target"
                                : ", outside the target (" + row.accuracy_failure + ")");
      for (std::size_t i = 0; i < events; ++i) {
        line += ", " + result_.event_names[i] + " " +
                (std::isnan(row.event_times[i]) ? std::string("missed")
                                                : "error " + format_g(row.event_relative_errors[i]) +
                                                      " (relative)");
      }
    }
    say(line);
    result_.rows.push_back(row);
    return row;
  }

  void run_fixed_grid(const std::string& integrator) {
    if (!options_.dts.empty()) {
      std::vector<double> dts = options_.dts;
      std::sort(dts.rbegin(), dts.rend());
      for (double dt : dts) run_point(integrator, dt, 0.0);
      return;
    }
    // Default grid: from past the predicted instability limit to well inside it, coarse to
    // fine, pruned by the time budget.
    // rk4 finer than 4x the reference step would measure the reference, not itself.
    const double finest = core::integrator_traits(integrator).order >=
                                  core::integrator_traits(result_.reference_integrator).order
                              ? 4.0 * result_.reference_dt
                              : result_.reference_dt;
    StabilityLimit& limit = limit_of(integrator);
    core::StepLimit predicted;
    predicted.max_step = limit.predicted;
    predicted.unbounded = limit.predicted_unbounded;
    predicted.chatter_free_step = limit.chatter_free;
    predicted.skipped = limit.predicted_skipped;
    const StepGrid grid =
        default_step_grid(scene_.run.dt, predicted, finest, result_.duration / 4.0);
    limit.grid_past_limit = grid.past_limit;
    if (!grid.note.empty()) note(integrator + ": " + grid.note);
    // The time of a run grows as 1 / dt: the last stable run predicts the next one's.
    double last_wall = 0.0, last_dt = 0.0;
    for (double dt : grid.steps) {
      const double expected = last_wall * last_dt / dt;
      if (last_wall > 0.0 && expected > options_.max_run_seconds) {
        note(integrator + ": steps of " + format_g(dt) +
             " s and below not run (the next would take about " + format_g(expected, 2) +
             " s, over the " + format_g(options_.max_run_seconds, 2) + " s per run budget)");
        break;
      }
      const StudyRow row = run_point(integrator, dt, 0.0);
      if (row.status == "ok") {
        last_wall = row.wall_seconds;
        last_dt = dt;
      }
    }
  }

  void run_adaptive_grid(const std::string& integrator) {
    std::vector<double> tolerances = options_.tolerances;
    const bool defaults = tolerances.empty();
    if (defaults) tolerances = {1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};
    std::sort(tolerances.rbegin(), tolerances.rend());
    double last_wall = 0.0;
    for (double tol : tolerances) {
      if (defaults && last_wall > 0.0 && 2.0 * last_wall > options_.max_run_seconds) {
        note(integrator + ": tolerances below " + format_g(tol * 10.0) + " not run (time budget)");
        break;
      }
      const StudyRow row = run_point(integrator, scene_.run.dt, tol);
      if (row.status == "ok") last_wall = row.wall_seconds;
    }
  }

  const StudyOptions& options_;
  const StudyLog& log_;
  scene::Scene scene_;
  StudyResult result_;
  StudyReference reference_;  // after scene_ and result_, which it reads and fills
  StepLimitSearch limits_;
  std::vector<std::string> integrators_;
};

}  // namespace

std::vector<std::string> key_signal_columns(const std::vector<std::string>& columns) {
  std::vector<std::string> keys;
  for (const auto& name : columns) {
    const auto first = name.find('.');
    const auto last = name.rfind('.');
    if (first == std::string::npos || last == first) continue;
    const std::string signal = name.substr(first + 1, last - first - 1);
    if (signal == "p" || signal == "v" || signal == "theta") keys.push_back(name);
  }
  return keys;
}

OrderEstimate observed_order(const StudyResult& result, const std::string& integrator) {
  OrderEstimate estimate;
  estimate.integrator = integrator;
  std::vector<double> xs, ys;
  const double floor = std::isfinite(result.reference_noise) ? kNoiseFactor * result.reference_noise : 0.0;
  for (const auto& row : result.rows) {
    if (row.integrator != integrator || row.tolerance > 0.0 || row.status != "ok") continue;
    if (!(row.key_error > floor && row.key_error < kSaturatedError)) continue;
    xs.push_back(std::log(row.dt));
    ys.push_back(std::log(row.key_error));
    estimate.dt_min = estimate.points == 0 ? row.dt : std::min(estimate.dt_min, row.dt);
    estimate.dt_max = std::max(estimate.dt_max, row.dt);
    ++estimate.points;
  }
  if (estimate.points < 2 || estimate.dt_max / estimate.dt_min < 1.5) {
    estimate.order = kNaN;
    return estimate;
  }
  double mx = 0.0, my = 0.0;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    mx += xs[i];
    my += ys[i];
  }
  mx /= static_cast<double>(xs.size());
  my /= static_cast<double>(ys.size());
  double sxy = 0.0, sxx = 0.0;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    sxy += (xs[i] - mx) * (ys[i] - my);
    sxx += (xs[i] - mx) * (xs[i] - mx);
  }
  estimate.order = sxy / sxx;
  return estimate;
}

StudyResult run_study(const StudyOptions& options, const StudyLog& log) {
  Study study(options, log);
  return study.run();
}

}  // namespace stiction::services
