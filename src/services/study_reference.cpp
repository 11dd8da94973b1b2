#include "services/study_reference.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

#include "core/capabilities.hpp"

namespace stiction::services {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The event kinds measured per element: its first stick and its first slip.
constexpr const char* kEventKinds[] = {"stick", "slip"};

std::string format_g(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.3g", value);
  return buffer;
}

double first_event(const core::RunResult& run, const std::string& element,
                   const std::string& kind) {
  for (const auto& history : run.slip_events) {
    if (history.component != element) continue;
    const double t =
        kind == "stick" ? history.monitor.stick_time() : history.monitor.first_slip();
    return t >= 0.0 ? t : kNaN;
  }
  return kNaN;
}

}  // namespace

StudyReference::StudyReference(scene::Scene& scene, double target_error, StudyResult& result)
    : scene_(scene), target_error_(target_error), result_(result), rule_(read_judge_rule(scene)) {
  std::vector<std::string> columns{"t"};
  for (auto& c : scene_.network->signal_columns()) columns.push_back(std::move(c));
  result_.key_signals = key_signal_columns(columns);
  if (result_.key_signals.empty()) {
    throw scene::InputError(scene_.name +
                            ": the scene has no key signals (*.p.*, *.v.*, *.theta.*) to compare");
  }
  for (const auto& name : result_.key_signals) {
    const auto it = std::find(columns.begin(), columns.end(), name);
    key_columns_.push_back(static_cast<int>(it - columns.begin()));
  }
  for (const auto& imp : scene_.network->impedances()) {
    if (core::capabilities_of(*imp).slip == nullptr) continue;
    result_.slip_components.push_back(imp->name());
    for (const char* kind : kEventKinds) events_.push_back({imp->name(), kind});
  }
}

void StudyReference::run(const core::RunOptions& reference, const core::RunOptions& twice) {
  reference_run_ = core::simulate(*scene_.network, reference);
  const core::RunResult& ref = reference_run_;
  if (ref.instability) {
    throw scene::InputError("--reference-dt " + format_g(reference.dt) +
                            ": the reference run (rk4) went unstable at t = " +
                            format_g(ref.instability->time) + " s in '" +
                            ref.instability->component + "'; pass a smaller --reference-dt");
  }
  result_.reference_steps = ref.steps;
  result_.reference_wall_seconds = ref.wall_seconds;
  // Measured from now on: the events the reference has.
  const StudyMeasurement all = measure(ref);
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
  scales_ = MotionScales(ref.trajectory);
  // The reference's own error: rk4 at twice its step against it.
  const core::RunResult check = core::simulate(*scene_.network, twice);
  if (check.instability) {
    result_.reference_noise = result_.reference_event_noise = result_.reference_accuracy_noise =
        kNaN;
    return;
  }
  const StudyMeasurement m = measure(check);
  result_.reference_noise = key_error(signal_errors(m, twice.dt)).first;
  result_.reference_accuracy_noise = accuracy(check).worst;
  result_.reference_event_noise = events_.empty() ? kNaN : 0.0;
  for (std::size_t i = 0; i < m.event_times.size(); ++i) {
    const double rel = std::abs(m.event_times[i] - reference_.event_times[i]) /
                       std::abs(reference_.event_times[i]);
    if (!(rel <= result_.reference_event_noise)) result_.reference_event_noise = rel;
  }
}

StudyMeasurement StudyReference::measure(const core::RunResult& run) const {
  StudyMeasurement m;
  for (int c : key_columns_) m.key.push_back(run.trajectory.column(c));
  for (const auto& [element, kind] : events_) {
    m.event_times.push_back(first_event(run, element, kind));
  }
  return m;
}

StudyAccuracy StudyReference::accuracy(const core::RunResult& run) const {
  ComparisonSetup setup;
  setup.rule = rule_;
  setup.rule.event_tolerance = setup.rule.final_tolerance = target_error_;
  setup.scales = &scales_;
  setup.run_label = "the run";
  setup.other_label = "the reference";
  const RunComparison c = compare_runs(*scene_.network, run, reference_run_, setup);
  StudyAccuracy a;
  const bool any_event = std::any_of(c.events.begin(), c.events.end(),
                                     [](const ComparedQuantity& q) { return q.judged; });
  a.event_time_error = any_event ? c.worst_event : kNaN;
  a.final_value_error = c.worst_final;
  a.worst = std::max(c.worst_event, c.worst_final);
  a.meets = c.accurate();
  a.worst_name = c.accurate() ? c.worst_name : c.reasons.front();
  return a;
}

// The rows on a step of the run only: the others are interpolated linearly between two steps,
// an O(dt^2) error of the output, not of the integrator (it would cap rk4's observed order at
// 2). A step that is no fraction of the output interval (the default grid's steps around the
// predicted limits) lands on few rows or none after t = 0: with fewer than 10 such rows, every
// row is compared.
std::vector<double> StudyReference::signal_errors(const StudyMeasurement& run, double dt) const {
  std::vector<bool> use;
  const std::size_t all =
      run.key.empty() ? 0 : std::min(run.key[0].size(), reference_.key[0].size());
  std::size_t on_steps = 0;
  for (std::size_t r = 0; r < all; ++r) {
    const double steps = static_cast<double>(r) / result_.output_rate / dt;
    use.push_back(dt <= 0.0 || std::abs(steps - std::round(steps)) < 1e-6);
    if (r > 0 && use.back()) ++on_steps;
  }
  if (on_steps < std::min<std::size_t>(10, all > 0 ? all - 1 : 0) || on_steps == 0) {
    use.assign(all, true);
  }
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

std::pair<double, std::string> StudyReference::key_error(const std::vector<double>& errors) const {
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
void StudyReference::set_scales() {
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

}  // namespace stiction::services
