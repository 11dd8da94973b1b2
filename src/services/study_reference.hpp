// What `stiction study` measures every run against: its reference (rk4 at a much smaller
// step), run once. A run is measured two ways, and both live here so that a grid row, a
// bisection probe and the recommendation are judged alike:
//   - the key-signal errors (study.csv's columns, the observed order): the largest
//     |run - reference| of each key signal over the rows both have, against the scale of its
//     vector in the reference;
//   - the accuracy against the target: the one comparison of two runs that `run`'s accuracy
//     verdict uses (run_comparison.hpp), with the scene's [accuracy] rule, its default
//     tolerances set to the target and the reference taken as the truth.
// The reference's own error (rk4 at twice its step against it) is measured too: errors near
// it are the reference's, not the run's.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/simulation.hpp"
#include "scene/scene.hpp"
#include "services/run_comparison.hpp"
#include "services/study.hpp"

namespace stiction::services {

// What the study reads from one run: the key columns and the measured event times.
struct StudyMeasurement {
  std::vector<std::vector<double>> key;  // per key signal, per row
  std::vector<double> event_times;       // per measured event, NaN: none
};

// One run against the target (StudyRow's accuracy fields).
struct StudyAccuracy {
  double event_time_error = 0.0;  // NaN: no events
  double final_value_error = 0.0;
  double worst = 0.0;      // the larger of the two (infinity: outside the target)
  bool meets = false;      // every judged quantity within its tolerance
  std::string worst_name;  // the worst quantity, or the first reason it is not within
};

class StudyReference {
 public:
  // Reads the scene's key signals, its slip elements (their first stick and first slip are
  // the events measured) and its [accuracy] rule into `result`.
  StudyReference(scene::Scene& scene, double target_error, StudyResult& result);

  // Runs the reference at `run` (the study's options at result.reference_dt) and rk4 at
  // twice its step; keeps the events the reference has, sets the key scales and the
  // reference's noise in `result`. Throws scene::InputError when the reference is unstable.
  void run(const core::RunOptions& reference, const core::RunOptions& twice);

  StudyMeasurement measure(const core::RunResult& run) const;
  StudyAccuracy accuracy(const core::RunResult& run) const;
  // Largest error of each key signal over the rows both runs have. With a fixed step dt
  // (> 0), only the rows on a step of the run when there are at least ten (see the .cpp).
  std::vector<double> signal_errors(const StudyMeasurement& run, double dt) const;
  // max over key signals of error / scale, and the signal that attains it.
  std::pair<double, std::string> key_error(const std::vector<double>& errors) const;

  std::size_t event_count() const { return events_.size(); }
  // The reference's time of measured event i.
  double event_time(std::size_t i) const { return reference_.event_times[i]; }
  const JudgeRule& rule() const { return rule_; }

 private:
  void set_scales();

  scene::Scene& scene_;
  double target_error_;
  StudyResult& result_;
  JudgeRule rule_;  // the scene's [accuracy]
  std::vector<int> key_columns_;
  std::vector<std::pair<std::string, std::string>> events_;  // (element, kind) measured
  StudyMeasurement reference_;
  core::RunResult reference_run_;  // the reference itself, for the one comparison
  MotionScales scales_;
};

}  // namespace stiction::services
