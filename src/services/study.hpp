// `stiction study SCENE`: speed against accuracy of the integrators on one scene.
//
// For each integrator and step size (tolerance for rk4_adaptive) the scene is simulated in
// this process and measured: wall time of the simulation alone (median of repeats), steps,
// network evaluations, the largest error of the scene's key signals (`*.p.*`, `*.v.*` of
// bodies, `*.theta.*` of arms and joints) over the common output rows against a reference
// run (rk4 at a much smaller step), and the errors of the events of each contact or joint
// (its first stick and its first slip, whichever the reference has) against the
// reference's. A run that goes unstable is a row with status `unstable`, never an error. A
// run meets the accuracy target when every event time and every final value of a key signal
// is within `target_error` of the reference's (event times relative to the duration, values
// relative to the signal's scale). The default grid of a fixed-step integrator runs from well
// inside to past the instability limit `stiction check` predicts (study_grid.hpp). Then, for
// each fixed-step integrator, the largest step is found twice by bisection over whole runs of
// the scene, by stability (the run ends without instability) and by accuracy (it meets the
// target), set beside core::predict_step_limit's prediction, and the cheapest run that meets
// the target is recommended.
//
// The measuring (this header) is apart from the reporting (study_report.cpp: study.csv,
// study.md, work_precision.png) and from the command line (study_command.cpp).
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/simulation.hpp"
#include "image/image.hpp"
#include "plot/figure.hpp"
#include "scene/scene.hpp"
#include "services/step_check.hpp"
#include "text/font.hpp"

namespace stiction::services {

struct StudyOptions {
  scene::SceneSource scene;              // bundled name or path, or a TOML text
  std::vector<std::string> overrides;    // --set KEY=VALUE
  std::vector<std::string> integrators;  // empty: every integrator
  std::vector<double> dts;               // empty: around the predicted limits (study_grid.hpp)
  std::vector<double> tolerances;        // empty: 1e-4 .. 1e-10 (rk4_adaptive)
  std::optional<double> reference_dt;    // empty: scene dt / 16
  int repeats = 3;                       // timing repeats (fewer for long runs)
  // Default grids only: a finer step is not run when the previous run of the same
  // integrator, doubled, would take longer than this (wall seconds). The finest default
  // step is the reference's (rk4: 4x the reference's).
  double max_run_seconds = 3.0;
  // Timing repeats are cut so that one grid point takes at most about this long.
  double repeat_budget_seconds = 2.0;
  bool bisect = true;                        // stability limits (fixed-step integrators)
  int stability_samples = kStatesPerRegime;  // per regime, for core::predict_step_limit (as check)
  double bisection_precision = 0.01;         // relative width of the final bracket
  // Relative accuracy a run must meet (event times and final values), in (0, 1).
  double target_error = 1e-3;
};

// One run of the grid.
struct StudyRow {
  std::string integrator;
  double dt = 0.0;         // the step; rk4_adaptive: its first step
  double tolerance = 0.0;  // rk4_adaptive only, else 0
  std::string status;      // "ok" or "unstable"
  std::optional<core::Instability> instability;
  long steps = 0;
  long evaluations = 0;
  double wall_seconds = 0.0;  // median over `repeats`
  int repeats = 0;
  // Largest |run - reference| of each key signal over the rows both have (NaN if unstable).
  std::vector<double> signal_errors;
  // max over key signals of signal_error / scale of the signal (see StudyResult::key_scales).
  double key_error = 0.0;
  std::string worst_signal;
  // Per event (StudyResult::event_names): its time in this run (NaN: none) and the error
  // against the reference's, absolute (s) and relative (to the reference time).
  std::vector<double> event_times;
  std::vector<double> event_errors;
  std::vector<double> event_relative_errors;
  double max_event_relative_error = 0.0;  // NaN when an event is missing or there are none
  // CPU time of the simulation (the thread CPU clock), median over `repeats` like wall_seconds.
  double cpu_seconds = 0.0;
  // Accuracy against the target: the largest |t - t_ref| / duration over the events
  // (infinity when the run misses one, NaN without events or when unstable) and the largest
  // |x(end) - x_ref(end)| / scale over the key signals (NaN when unstable).
  double event_time_error = 0.0;
  double final_value_error = 0.0;
  bool meets_target = false;
  // What breaks the target when it is not met: "unstable", "<element> <kind> time" or
  // "<signal> final"; empty when met.
  std::string accuracy_failure;
};

// Observed order of one fixed-step integrator: least-squares slope of log(key error)
// against log(dt) over its usable rows (stable, not saturated, above the reference's noise).
struct OrderEstimate {
  std::string integrator;
  double order = 0.0;  // NaN with fewer than two usable rows
  int points = 0;
  double dt_min = 0.0, dt_max = 0.0;
};

struct StabilityLimit {
  std::string integrator;
  double predicted = 0.0;  // core::predict_step_limit (0: none found)
  bool predicted_unbounded = false;
  bool predicted_skipped = false;  // too many states for the step analysis: no prediction
  double predicted_time = 0.0;  // time of the sampled state that limits it
  double chatter_free = 0.0;    // largest step at which no stuck friction chatters either
  double bisected = 0.0;        // largest step found stable by whole runs (0: none)
  double unstable_above = 0.0;  // smallest step found unstable (the bracket's top)
  int runs = 0;                 // runs spent by the bisection
  std::string note;             // e.g. "stable at every step tried"
  // Largest step by accuracy (StudyRow::meets_target): the largest step found within the
  // target with every grid step below it within the target too, bisected where the grid
  // brackets it; 0: none. `inaccurate_above` is the bracket's top (0: none found) and
  // `accuracy_failure` what breaks the target there.
  double accurate = 0.0;
  double inaccurate_above = 0.0;
  std::string accuracy_failure;
  int accuracy_runs =
      0;  // runs of the accuracy bisection (runs shared with the stability one not counted)
  std::string accuracy_note;
  // The run at `accurate` (its cost and its errors), for the recommendation.
  long accurate_evaluations = 0;
  double accurate_cpu_seconds = 0.0;
  double accurate_event_time_error = 0.0;
  double accurate_final_value_error = 0.0;
  bool accurate_bisected = false;  // `accurate` is a bisection run, not a grid row
  // Steps of the default grid above the predicted limit (0: the grid does not pass it).
  int grid_past_limit = 0;
};

// A run within the target, as a recommendation. The candidates of an integrator are its grid
// rows within the target whose step (tolerance) is at most its largest accurate one (every
// finer run within the target too) and the run at its bisected largest accurate step; its
// candidate is the one with the fewest network evaluations. The recommendation is the
// integrators' candidate with the least CPU time per simulated second, timed again (median of
// the repeats) so that all candidates are timed alike.
struct Recommendation {
  std::string integrator;               // empty: no run met the target
  double dt = 0.0;                      // the step; rk4_adaptive: its first step
  double tolerance = 0.0;               // rk4_adaptive only
  double evaluations_per_second = 0.0;  // network evaluations per simulated second
  double cpu_per_second = 0.0;          // CPU seconds per simulated second
  double event_time_error = 0.0;
  double final_value_error = 0.0;
  bool bisected = false;  // the run is the bisection's, not a grid row
  int repeats = 0;        // timing runs behind cpu_per_second (the median)
  // `run`'s own accuracy verdict at this setting ("accurate" once confirmed), and what was
  // changed to get there (a margin from the stability limit, a smaller step).
  std::string run_verdict;
  std::string note;
};

struct StudyResult {
  std::string scene;
  double scene_dt = 0.0;
  double duration = 0.0;
  double output_rate = 0.0;
  std::string reference_integrator = "rk4";
  double reference_dt = 0.0;
  long reference_steps = 0;
  double reference_wall_seconds = 0.0;
  // Key error of rk4 at 2 x reference_dt against the reference: errors near this are the
  // reference's own, so they are left out of the order fits.
  double reference_noise = 0.0;
  // Likewise for the event times: the largest relative difference of rk4 at 2 x
  // reference_dt from the reference (NaN without events).
  double reference_event_noise = 0.0;
  std::vector<std::string> key_signals;
  std::vector<double> key_scales;  // max |value| of each key signal's vector in the reference
  std::vector<std::string> slip_components;  // elements with a slip speed
  // The events measured: "<element> stick" (its first stick) and "<element> slip" (its first
  // slip), for each one the reference has, with the reference's times.
  std::vector<std::string> event_names;
  std::vector<double> reference_event_times;
  std::vector<StudyRow> rows;
  std::vector<OrderEstimate> orders;
  std::vector<StabilityLimit> limits;
  std::vector<std::string> notes;  // pruning and other remarks, printed in study.md
  double total_seconds = 0.0;
  double target_error = 1e-3;
  // The accuracy measure (the worse of the event-time and final-value errors) of rk4 at
  // 2 x reference_dt against the reference: a target near this measures the reference (NaN:
  // that run went unstable).
  double reference_accuracy_noise = 0.0;
  std::vector<Recommendation> candidates;  // one per integrator with a run within the target
  Recommendation recommendation;           // the cheapest candidate (none: empty integrator)
};

// Progress lines (one per run) for stderr; may be empty.
using StudyLog = std::function<void(const std::string&)>;

StudyResult run_study(const StudyOptions& options, const StudyLog& log = {});

// Key signals among trajectory columns: `<component>.p.<axis>`, `<component>.v.<axis>`,
// `<component>.theta.<axis>`.
std::vector<std::string> key_signal_columns(const std::vector<std::string>& columns);

// The usable rows of `integrator` and the slope through them (see OrderEstimate).
OrderEstimate observed_order(const StudyResult& result, const std::string& integrator);

// Each integrator's candidate (see Recommendation), from the rows and the limits, with the
// CPU time of the run that gave it (study_recommendation.cpp).
std::vector<Recommendation> recommendation_candidates(const StudyResult& result);
// The candidate with the least CPU time per simulated second (ties: fewer evaluations).
Recommendation cheapest(const std::vector<Recommendation>& candidates);
// rk4_adaptive's largest tolerance within the target with every tighter one within it too
// (0: none).
double largest_accurate_tolerance(const StudyResult& result, const std::string& integrator);

// Reports (study_report.cpp).
std::string study_csv(const StudyResult& result);
std::string study_markdown(const StudyResult& result);
image::Image work_precision_figure(const StudyResult& result, text::Font& font);
// The figure work_precision_figure draws (for checks of its layout).
plot::Figure work_precision_plot(const StudyResult& result);
// Writes study.csv, study.md and work_precision.png into `out`, each atomically.
void write_study(const StudyResult& result, const std::filesystem::path& out);

}  // namespace stiction::services
