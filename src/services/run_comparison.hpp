// How far one run of a scene is from another run of the same scene (issue 35 item 1): the
// one comparison that `run`'s accuracy companion (accuracy.hpp), `study` (against its
// reference), the suggested step and `check`'s trials (suggest_step.hpp) all call, so that
// "accurate" means the same thing in every command. docs/accuracy.md, "What is judged".
//
//   (run, other, setup) => per quantity: value, estimated error, tolerance, judged; the
//                          repeated-event counts that differ; the reasons a judged quantity
//                          fails.
//
// Quantities come in classes (quantity_classes()); a scene's `[accuracy]` table picks which
// are judged (`judge`, `ignore`, per class or per `COMPONENT.CLASS`) and their tolerances.
//   - Events of each element with a slip speed and of each body with several contact points:
//     the first and the last of each kind. The error of an event time is the larger of
//     `event_factor` |t_run - t_other| and how precisely the run located it
//     (core::SlipEvent::uncertainty: an onset found between two steps is known to a step,
//     whatever the other run says). Its tolerance is relative to the event's own time scale:
//     the longer of the time since the element's previous event of its kind (or the start)
//     and the time to its next one (or the end), not the run's duration.
//   - When two runs have a different number of events of one kind, the counts are "not
//     converged" (micro-bounces, chatter): reported with both counts, judged only when the
//     rule judges `event_counts`; the last event of that kind is then not the same event in
//     the two runs and is not judged. The first one still is.
//   - Final values of bodies and joints (position, velocity, orientation, spin, joint angle,
//     joint speed): error `final_factor` |x_run - x_other|, against a scale from the motion
//     the signal actually had (MotionScales): the path it travelled for positions, angles and
//     orientations, the largest magnitude for speeds; never below 1% of the largest such
//     scale of the same class in the scene, so that a joint that never moved is judged
//     against the motion of the mechanism it belongs to, not in microradians.
//   - Forces, slips and internal states of impedances (`element_state`) get an estimate and
//     are never judged by default.
#pragma once

#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/network.hpp"
#include "core/row_sink.hpp"
#include "core/simulation.hpp"
#include "scene/scene.hpp"

namespace stiction::services {

// Every class of quantity, in report order, and those judged when the scene says nothing.
const std::vector<std::string>& quantity_classes();
const std::vector<std::string>& default_judged_classes();

// Which quantities decide a verdict, and their relative tolerances (scene `[accuracy]`).
struct JudgeRule {
  std::set<std::string> classes;                   // judged classes
  std::set<std::string> judge, ignore;             // "COMPONENT.CLASS" exceptions
  std::map<std::string, double> tolerances;        // per class, relative
  double event_tolerance = 1e-3;                   // default for event classes
  double final_tolerance = 1e-3;                   // default for final-value classes
  bool judges(const std::string& component, const std::string& cls) const;
  double tolerance(const std::string& cls) const;
};

// The rule of `[accuracy]` (docs/scene_format.md): `judge = [...]` and `ignore = [...]`
// (class names, or COMPONENT.CLASS), `tolerance = REL` for every class and
// `[accuracy.tolerances]` per class. Errors name the file, line and key (InputError).
JudgeRule read_judge_rule(const scene::Scene& scene);

// Per trajectory column, from a run's rows: the largest magnitude and, per signal (a column
// without its axis: "ball.p"), the path travelled (the sum over rows of the Euclidean norm of
// the signal's change). A RowSink, so a companion that keeps no rows can measure itself.
class MotionScales final : public core::RowSink {
 public:
  MotionScales() = default;
  explicit MotionScales(const core::Trajectory& trajectory);
  void write(const double* rows, std::size_t count, std::size_t columns) override;
  double largest(std::size_t column) const;
  // Of the signal that `column` belongs to.
  double travel(std::size_t column) const;
  double signal_largest(std::size_t column) const;
  void set_columns(const std::vector<std::string>& columns);

 private:
  std::vector<double> largest_;
  std::vector<int> group_;          // per column, its signal
  std::vector<double> travel_;      // per signal
  std::vector<double> group_largest_;
  std::vector<double> previous_;
  bool have_previous_ = false;
};

// The signal a column belongs to: the column without its axis ("ball.p.x" -> "ball.p",
// "arm.theta.0" -> "arm.theta"; "lane.n_force" stays).
std::string signal_of(const std::string& column);

struct ComparisonSetup {
  JudgeRule rule;
  // The run's error from the difference: Richardson's 2^p / (2^p - 1) against a companion at
  // half the step, 1 against a reference far finer.
  double final_factor = 1.0;
  // The same for event times, whose order is not the integrator's (an onset on a step
  // boundary converges at first order even under rk4): 2 against a half-step companion
  // bounds every order >= 1.
  double event_factor = 1.0;
  // Of the finer of the two runs (the scales of the final values), over the same columns.
  const MotionScales* scales = nullptr;
  std::string run_label = "the run";      // "dt = 1e-4 s"
  std::string other_label = "the other";  // "the companion (dt = 5e-5 s)"
};

struct ComparedQuantity {
  std::string name;       // "ground.first_stick", "box.first_slide", "ball.p.x"
  std::string component;  // element or body
  std::string cls;        // its class (quantity_classes())
  std::string kind;       // events: "stick", "slip", "open", "slide", ...; finals: ""
  double value = std::numeric_limits<double>::quiet_NaN();  // in the run
  double other = std::numeric_limits<double>::quiet_NaN();  // in the other run (NaN: none)
  std::optional<double> error;  // estimated error of the run's value; none: not comparable
  double located = 0.0;         // events: the run's location uncertainty (s)
  double scale = 0.0;           // events: own time scale (s, phase_scale); finals: the signal's
  double tolerance = 0.0;       // absolute
  bool judged = false;
  std::string note;  // why not comparable ("only in the run", "counts not converged")
  bool within() const { return error && *error <= tolerance; }
  // error / tolerance * relative tolerance: the error relative to the scale (infinity when
  // not comparable).
  double relative_error() const;
};

struct CountDifference {
  std::string component;
  std::string kind;
  std::size_t run = 0, other = 0;
  bool judged = false;
};

struct RunComparison {
  std::vector<ComparedQuantity> events;
  std::vector<ComparedQuantity> finals;
  std::vector<CountDifference> not_converged;
  std::vector<std::string> judged;   // names of the quantities the verdict rests on
  std::vector<std::string> reasons;  // each judged quantity that fails, in words
  bool accurate() const { return reasons.empty(); }
  // The worst judged relative error among events and among finals (0 when none; infinity
  // when a judged event is missing), and the name of the worst quantity overall.
  double worst_event = 0.0, worst_final = 0.0;
  std::string worst_name;
};

// Compares `run` with `other` (same scene, same columns). The finals are the last rows.
RunComparison compare_runs(const core::Network& network, const core::RunResult& run,
                           const core::RunResult& other, const ComparisonSetup& setup);

}  // namespace stiction::services
