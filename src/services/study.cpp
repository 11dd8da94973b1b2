#include "services/study.hpp"

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <stdexcept>
#include <utility>

#include "services/accuracy.hpp"
#include "services/pilot.hpp"
#include "services/run_comparison.hpp"
#include "services/study_grid.hpp"
#include "core/integrator.hpp"
#include "core/stability.hpp"
#include "scene/scene.hpp"
#include "sys/interrupt.hpp"

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

// What the study needs from one reference-like run: the key columns and the event times.
struct Measured {
  std::vector<std::vector<double>> key;  // per key signal, per row
  std::vector<double> event_times;       // per measured event, NaN: none
  double final_time = 0.0;               // time of the last row
};

// One run measured against the target (StudyRow's accuracy fields).
struct Accuracy {
  double event_time_error = kNaN;  // NaN: no events
  double final_value_error = kNaN;
  double worst = 0.0;      // the larger of the two (infinity: outside the target)
  bool meets = false;      // every judged quantity within its tolerance
  std::string worst_name;  // the worst quantity, or the first reason it is not within
};

// A whole run at one step, kept so that the two bisections never run the same step twice.
struct Probe {
  bool stable = false;
  bool meets_target = false;
  std::string failure;
  long evaluations = 0;
  double cpu_seconds = 0.0;
  double event_time_error = kNaN;
  double final_value_error = kNaN;
};

// The event kinds measured per element: its first stick and its first slip.
constexpr const char* kEventKinds[] = {"stick", "slip"};

double first_event(const core::RunResult& run, const std::string& element, const std::string& kind) {
  for (const auto& history : run.slip_events) {
    if (history.component != element) continue;
    const double t = kind == "stick" ? history.monitor.stick_time() : history.monitor.first_slip();
    return t >= 0.0 ? t : kNaN;
  }
  return kNaN;
}

class Study {
 public:
  Study(const StudyOptions& options, const StudyLog& log)
      : options_(options),
        log_(log),
        scene_(scene::load_scene(options.scene, options.overrides)),
        judge_rule_(read_judge_rule(scene_)) {
    result_.scene = scene_.name;
    result_.scene_dt = scene_.run.dt;
    result_.duration = scene_.run.duration;
    result_.output_rate = scene_.run.output_rate;
    result_.reference_dt = options.reference_dt.value_or(scene_.run.dt / 16.0);
    if (!(result_.reference_dt > 0.0)) throw scene::InputError("--reference-dt: must be > 0");
    std::vector<std::string> columns{"t"};
    for (auto& c : scene_.network->signal_columns()) columns.push_back(std::move(c));
    result_.key_signals = key_signal_columns(columns);
    if (result_.key_signals.empty()) {
      throw scene::InputError(scene_.name + ": the scene has no key signals (*.p.*, *.v.*, *.theta.*) to compare");
    }
    for (const auto& name : result_.key_signals) key_columns_.push_back(index_of(columns, name));
    for (const auto& imp : scene_.network->impedances()) {
      if (core::capabilities_of(*imp).slip == nullptr) continue;
      result_.slip_components.push_back(imp->name());
      for (const char* kind : kEventKinds) events_.push_back({imp->name(), kind});
    }
    integrators_ = options.integrators.empty() ? core::integrator_names() : options.integrators;
    const auto known = core::integrator_names();
    for (const auto& name : integrators_) {
      if (std::find(known.begin(), known.end(), name) == known.end()) {
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
    if (any_fixed && (options_.dts.empty() || options_.bisect)) predict_limits();
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
        bisect(limit.integrator, limit);
        bisect_accuracy(limit.integrator, limit);
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
  static int index_of(const std::vector<std::string>& columns, const std::string& name) {
    const auto it = std::find(columns.begin(), columns.end(), name);
    return static_cast<int>(it - columns.begin());
  }

  void say(const std::string& line) const {
    if (log_) log_(line);
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

  Measured measure(const core::RunResult& run) const {
    Measured m;
    const core::Trajectory& tr = run.trajectory;
    for (int c : key_columns_) m.key.push_back(tr.column(c));
    const std::vector<double> times = tr.column(0);
    m.final_time = times.empty() ? kNaN : times.back();
    for (const auto& [element, kind] : events_) m.event_times.push_back(first_event(run, element, kind));
    return m;
  }

  // How far a run is from the reference, by the one comparison of two runs that `run`'s
  // accuracy verdict uses (run_comparison.hpp): the scene's [accuracy] rule, its default
  // tolerances set to the target, the reference taken as the truth (factors 1).
  Accuracy accuracy(const core::RunResult& run) const {
    ComparisonSetup setup;
    setup.rule = judge_rule_;
    setup.rule.event_tolerance = setup.rule.final_tolerance = options_.target_error;
    setup.scales = &reference_scales_;
    setup.run_label = "the run";
    setup.other_label = "the reference";
    const RunComparison c = compare_runs(*scene_.network, run, reference_run_, setup);
    Accuracy a;
    const bool any_event = std::any_of(c.events.begin(), c.events.end(),
                                       [](const ComparedQuantity& q) { return q.judged; });
    a.event_time_error = any_event ? c.worst_event : kNaN;
    a.final_value_error = c.worst_final;
    a.worst = std::max(c.worst_event, c.worst_final);
    a.meets = c.accurate();
    a.worst_name = c.accurate() ? c.worst_name : c.reasons.front();
    return a;
  }

  // Largest error of each key signal over the rows both runs have. With a fixed step dt
  // (> 0), only the rows that fall on a step of the run are compared when there are any:
  // the others are interpolated linearly between two steps, an O(dt^2) error of the output,
  // not of the integrator (it would cap rk4's observed order at 2). A step that is no
  // fraction of the output interval (the default grid's steps around the predicted limits)
  // lands on few rows or none after t = 0: with fewer than 10 such rows, every row is compared.
  std::vector<double> signal_errors(const Measured& run, double dt) const {
    std::vector<bool> use;
    const std::size_t all = run.key.empty() ? 0 : std::min(run.key[0].size(), reference_.key[0].size());
    std::size_t on_steps = 0;
    for (std::size_t r = 0; r < all; ++r) {
      const double steps = static_cast<double>(r) / result_.output_rate / dt;
      use.push_back(dt <= 0.0 || std::abs(steps - std::round(steps)) < 1e-6);
      if (r > 0 && use.back()) ++on_steps;
    }
    if (on_steps < std::min<std::size_t>(10, all > 0 ? all - 1 : 0) || on_steps == 0)
      use.assign(all, true);
    std::vector<double> errors;
    for (std::size_t s = 0; s < run.key.size(); ++s) {
      const auto& a = run.key[s];
      const auto& b = reference_.key[s];
      const std::size_t rows = std::min(a.size(), b.size());
      double worst = 0.0;
      for (std::size_t r = 0; r < rows; ++r) {
        if (!use[r]) continue;
        const double e = std::abs(a[r] - b[r]);
        worst = std::isfinite(e) ? std::max(worst, e) : std::numeric_limits<double>::infinity();
      }
      errors.push_back(worst);
    }
    return errors;
  }

  // max over signals of error / scale, and the signal that attains it.
  std::pair<double, std::string> key_error(const std::vector<double>& errors) const {
    double worst = 0.0;
    std::string name;
    for (std::size_t s = 0; s < errors.size(); ++s) {
      const double e = errors[s] / result_.key_scales[s];
      if (!(e <= worst)) {  // also takes NaN and infinity
        worst = e;
        name = result_.key_signals[s];
      }
    }
    return {worst, name};
  }

  // Scale of each key signal: the largest |value| of any axis of its vector signal
  // (`sphere.p.*`) in the reference, so that one axis that stays near zero (the height of a
  // rolling sphere) is measured against the size of the motion, not against itself.
  void set_scales() {
    std::map<std::string, double> group_max;
    auto group_of = [](const std::string& name) { return name.substr(0, name.rfind('.')); };
    for (std::size_t s = 0; s < reference_.key.size(); ++s) {
      double m = 0.0;
      for (double v : reference_.key[s]) m = std::max(m, std::abs(v));
      double& g = group_max[group_of(result_.key_signals[s])];
      g = std::max(g, m);
    }
    for (const auto& name : result_.key_signals) {
      const double g = group_max[group_of(name)];
      result_.key_scales.push_back(g > 0.0 ? g : 1.0);
    }
  }

  void run_reference() {
    const double h = result_.reference_dt;
    say("reference: rk4, dt = " + format_g(h) + " s ...");
    reference_run_ =
        core::simulate(*scene_.network, options_for(result_.reference_integrator, h, 0.0));
    const core::RunResult& ref = reference_run_;
    if (ref.instability) {
      throw scene::InputError("--reference-dt " + format_g(h) +
                              ": the reference run (rk4) went unstable at t = " +
                              format_g(ref.instability->time) + " s in '" +
                              ref.instability->component + "'; pass a smaller --reference-dt");
    }
    result_.reference_steps = ref.steps;
    result_.reference_wall_seconds = ref.wall_seconds;
    // Measured from now on: the events the reference has.
    const Measured all = measure(ref);
    std::vector<std::pair<std::string, std::string>> present;
    for (std::size_t i = 0; i < events_.size(); ++i) {
      if (std::isnan(all.event_times[i])) continue;
      present.push_back(events_[i]);
      result_.event_names.push_back(events_[i].first + " " + events_[i].second);
      result_.reference_event_times.push_back(all.event_times[i]);
    }
    events_ = std::move(present);
    reference_ = measure(ref);
    set_scales();
    reference_scales_ = MotionScales(ref.trajectory);
    // The reference's own error: rk4 at twice its step against it.
    core::RunResult check = core::simulate(
        *scene_.network, options_for(result_.reference_integrator, 2.0 * h, 0.0));
    if (check.instability) {
      result_.reference_noise = result_.reference_event_noise = result_.reference_accuracy_noise =
          kNaN;
    } else {
      const Measured m = measure(check);
      result_.reference_noise = key_error(signal_errors(m, 2.0 * h)).first;
      result_.reference_accuracy_noise = accuracy(check).worst;
      result_.reference_event_noise = events_.empty() ? kNaN : 0.0;
      for (std::size_t i = 0; i < m.event_times.size(); ++i) {
        const double rel = std::abs(m.event_times[i] - reference_.event_times[i]) /
                           std::abs(reference_.event_times[i]);
        if (!(rel <= result_.reference_event_noise)) result_.reference_event_noise = rel;
      }
    }
    std::string line = "reference: " + std::to_string(ref.steps) + " steps in " +
                       format_g(ref.wall_seconds) + " s; rk4 at 2x its step differs by " +
                       format_g(result_.reference_noise) + " (key error)";
    if (!events_.empty()) {
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
        on.rule = judge_rule_;  // at the study's target, as the rows were judged
        on.rule->event_tolerance = on.rule->final_tolerance = options_.target_error;
        const AccuracyEstimate e = estimate_accuracy(scene_, run, {}, on);
        const Accuracy a = accuracy(run);
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

    const Measured m = measure(first);
    const std::size_t events = events_.size();
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
      row.signal_errors = signal_errors(m, is_fixed_step(integrator) ? dt : 0.0);
      std::tie(row.key_error, row.worst_signal) = key_error(row.signal_errors);
      row.event_times = m.event_times;
      row.max_event_relative_error = events == 0 ? kNaN : 0.0;
      for (std::size_t i = 0; i < events; ++i) {
        const double ref = reference_.event_times[i];
        const double err = std::abs(m.event_times[i] - ref);
        row.event_errors.push_back(err);
        row.event_relative_errors.push_back(err / std::abs(ref));
        // A missing event (NaN) makes the row's event error NaN: it missed the event.
        if (!(row.event_relative_errors.back() <= row.max_event_relative_error)) {
          row.max_event_relative_error = row.event_relative_errors.back();
        }
      }
      const Accuracy a = accuracy(first);
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
      for (std::size_t i = 0; i < events_.size(); ++i) {
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

  void note(const std::string& text) {
    result_.notes.push_back(text);
    say(text);
  }

  // A whole run of the scene at step h, measured once: the stability bisection and the
  // accuracy bisection share it. `runs` counts the runs actually made.
  const Probe& probe(const std::string& integrator, double h, int& runs) {
    const auto key = std::make_pair(integrator, h);
    const auto found = probes_.find(key);
    if (found != probes_.end()) return found->second;
    ++runs;
    Probe p;
    const core::RunResult run = simulate_timed(options_for(integrator, h, 0.0), p.cpu_seconds);
    p.evaluations = run.evaluations;
    p.stable = !run.instability;
    if (p.stable) {
      const Accuracy a = accuracy(run);
      p.event_time_error = a.event_time_error;
      p.final_value_error = a.final_value_error;
      p.meets_target = a.meets;
      if (!p.meets_target) p.failure = a.worst_name;
    } else {
      p.failure = "unstable";
    }
    return probes_.emplace(key, p).first->second;
  }

  // Whole run of the scene at step h: true if its monitor saw no instability.
  bool stable_run(const std::string& integrator, double h, StabilityLimit& limit) {
    return probe(integrator, h, limit.runs).stable;
  }

  StabilityLimit& limit_of(const std::string& integrator) {
    for (auto& limit : result_.limits) {
      if (limit.integrator == integrator) return limit;
    }
    throw std::logic_error("study: no predicted limit for " + integrator);
  }

  // What `stiction check` predicts, with its functions and its pilot run (bounded in steps),
  // so that the study's predicted limits are check's.
  void predict_limits() {
    const Pilot pilot = bounded_pilot(*scene_.network, scene_.run);
    say("predicted limits: sampling " + std::to_string(options_.stability_samples) +
        " states per regime (" + scene_.run.integrator + ", dt = " + format_g(scene_.run.dt) +
        (pilot.shortened ? ", first " + format_g(pilot.options.duration) + " s" : std::string()) +
        ")");
    if (pilot.shortened) {
      note("predicted limits from the first " + format_g(pilot.options.duration) + " s of " +
           format_g(scene_.run.duration) + " s (the pilot run's step budget, as `stiction check`)");
    }
    const auto states =
        core::sample_states(*scene_.network, pilot.options, options_.stability_samples);
    if (sys::interrupted()) throw sys::Interrupted{};
    for (const auto& integrator : integrators_) {
      if (!is_fixed_step(integrator)) continue;
      StabilityLimit limit;
      limit.integrator = integrator;
      const core::StepLimit predicted = core::predict_step_limit(
          *scene_.network, integrator, states, 1e-9, 1.0, &sys::interrupt_flag());
      if (sys::interrupted()) throw sys::Interrupted{};
      if (predicted.skipped) {  // too many states for the dense analysis: no prediction
        limit.predicted_skipped = true;
        note("predicted limits of " + integrator + ": skipped: the network has " +
             std::to_string(scene_.network->state_dim()) + " states, more than the " +
             std::to_string(core::kMaxAnalysedStates) +
             " the step analysis linearizes (docs/limits.md); the grid is the scene's dt x 8, 4, "
             "2, ...");
      }
      limit.predicted = predicted.max_step;
      limit.predicted_unbounded = predicted.unbounded;
      limit.predicted_time = predicted.limiting_time;
      limit.chatter_free = predicted.chatter_free_step;
      if (!predicted.skipped) {
        say("predicted " + integrator + ": unstable above " + format_g(limit.predicted, 4) +
            " s, stuck friction chatters above " + format_g(limit.chatter_free, 4) + " s");
      }
      result_.limits.push_back(limit);
    }
  }

  // Largest step within the target. Known runs (the grid's rows and the stability
  // bisection's probes) give the bracket: `hi` the smallest step outside the target, `lo`
  // the largest step within it below `hi`; bisected in log h as the stability limit is. The
  // accuracy need not be monotone in the step (a stick inside an impact moves with the
  // impact's timing): the answer is a step within the target with every known step below it
  // within the target too, and a known step within 1% above it outside.
  void bisect_accuracy(const std::string& integrator, StabilityLimit& limit) {
    struct Known {
      double h;
      bool meets;
      std::string failure;
    };
    std::vector<Known> known;
    for (const auto& row : result_.rows) {
      if (row.integrator == integrator)
        known.push_back({row.dt, row.meets_target, row.accuracy_failure});
    }
    for (const auto& [key, p] : probes_) {
      if (key.first == integrator) known.push_back({key.second, p.meets_target, p.failure});
    }
    double lo = 0.0, hi = std::numeric_limits<double>::infinity();
    std::string failure;
    for (const auto& k : known) {
      if (!k.meets && k.h < hi) {
        hi = k.h;
        failure = k.failure;
      }
    }
    for (const auto& k : known) {
      if (k.meets && k.h < hi) lo = std::max(lo, k.h);
    }
    if (lo == 0.0) {
      limit.inaccurate_above = hi;
      limit.accuracy_failure = failure;
      limit.accuracy_note = "no step tried meets the target";
      return;
    }
    if (!std::isfinite(hi)) {
      limit.accuracy_note = "within the target at every step tried, up to " + format_g(lo) + " s";
    } else {
      while (hi / lo > 1.0 + options_.bisection_precision) {
        const double mid = std::sqrt(lo * hi);
        const Probe& p = probe(integrator, mid, limit.accuracy_runs);
        if (p.meets_target) {
          lo = mid;
        } else {
          hi = mid;
          failure = p.failure;
        }
      }
      limit.inaccurate_above = hi;
      limit.accuracy_failure = failure;
    }
    limit.accurate = lo;
    // The run at `lo`: a grid row or a probe.
    const auto found = probes_.find(std::make_pair(integrator, lo));
    const StudyRow* row = nullptr;
    for (const auto& r : result_.rows) {
      if (r.integrator == integrator && r.dt == lo) row = &r;
    }
    if (row != nullptr) {
      limit.accurate_evaluations = row->evaluations;
      limit.accurate_cpu_seconds = row->cpu_seconds;
      limit.accurate_event_time_error = row->event_time_error;
      limit.accurate_final_value_error = row->final_value_error;
    } else if (found != probes_.end()) {
      limit.accurate_bisected = true;
      limit.accurate_evaluations = found->second.evaluations;
      limit.accurate_cpu_seconds = found->second.cpu_seconds;
      limit.accurate_event_time_error = found->second.event_time_error;
      limit.accurate_final_value_error = found->second.final_value_error;
    }
  }

  // Bracket from the grid (largest stable step below the smallest unstable one), widened by
  // doubling or halving when the grid has no unstable or no stable step, then bisected in
  // log h down to options_.bisection_precision.
  void bisect(const std::string& integrator, StabilityLimit& limit) {
    double lo = 0.0, hi = std::numeric_limits<double>::infinity();
    for (const auto& row : result_.rows) {
      if (row.integrator == integrator && row.status == "unstable") hi = std::min(hi, row.dt);
    }
    for (const auto& row : result_.rows) {
      if (row.integrator == integrator && row.status == "ok" && row.dt < hi) lo = std::max(lo, row.dt);
    }
    const double longest = result_.duration / 4.0;
    if (!std::isfinite(hi)) {
      double h = lo > 0.0 ? lo : scene_.run.dt;
      for (;;) {
        h *= 2.0;
        if (h > longest) {
          limit.bisected = lo;
          limit.note = "stable at every step tried, up to " + format_g(lo) + " s";
          return;
        }
        if (!stable_run(integrator, h, limit)) {
          hi = h;
          break;
        }
        lo = h;
      }
    }
    if (lo == 0.0) {
      double h = hi;
      for (int i = 0; i < 12; ++i) {
        h /= 2.0;
        const auto t0 = std::chrono::steady_clock::now();
        if (stable_run(integrator, h, limit)) {
          lo = h;
          break;
        }
        hi = h;
        const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (2.0 * took > options_.max_run_seconds) break;
      }
      if (lo == 0.0) {
        limit.unstable_above = hi;
        limit.note = "unstable at every step tried, down to " + format_g(hi) + " s";
        return;
      }
    }
    while (hi / lo > 1.0 + options_.bisection_precision) {
      const double mid = std::sqrt(lo * hi);
      if (stable_run(integrator, mid, limit)) {
        lo = mid;
      } else {
        hi = mid;
      }
    }
    limit.bisected = lo;
    limit.unstable_above = hi;
  }

  const StudyOptions& options_;
  const StudyLog& log_;
  scene::Scene scene_;
  std::vector<std::string> integrators_;
  std::vector<int> key_columns_;
  Measured reference_;
  core::RunResult reference_run_;  // the reference itself, for the one comparison
  MotionScales reference_scales_;
  JudgeRule judge_rule_;           // the scene's [accuracy]
  std::vector<std::pair<std::string, std::string>> events_;  // (element, kind) measured
  std::map<std::pair<std::string, double>, Probe> probes_;   // bisection runs by (integrator, h)
  StudyResult result_;
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
