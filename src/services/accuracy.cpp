#include "services/accuracy.hpp"

#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>

#include "core/integrator.hpp"
#include "core/row_sink.hpp"
#include "io/json_members.hpp"
#include "text/number_text.hpp"

namespace stiction::services {
namespace {

double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

template <typename... Numbers>
std::string format(const char* pattern, Numbers... numbers) {
  char text[240];
  std::snprintf(text, sizeof text, pattern, numbers...);
  return text;
}

// The signal a column belongs to: the column without its axis ("ball.p.x" -> "ball.p",
// "arm.theta.0" -> "arm.theta"; "lane.n_force" stays).
std::string signal_of(const std::string& column) {
  const auto dot = column.rfind('.');
  if (dot == std::string::npos) return column;
  const std::string last = column.substr(dot + 1);
  const bool axis = last == "x" || last == "y" || last == "z" || last == "w" ||
                    (!last.empty() && std::all_of(last.begin(), last.end(),
                                                  [](char ch) { return ch >= '0' && ch <= '9'; }));
  return axis ? column.substr(0, dot) : column;
}

// Keeps the companion's last row and, per column, the largest magnitude it took: the rows
// themselves are not needed, so the companion costs no memory that grows with the run.
class ScaleSink final : public core::RowSink {
 public:
  void write(const double* rows, std::size_t count, std::size_t columns) override {
    if (largest_.size() != columns) largest_.assign(columns, 0.0);
    for (std::size_t r = 0; r < count; ++r) {
      const double* row = rows + r * columns;
      for (std::size_t c = 0; c < columns; ++c) {
        if (std::isfinite(row[c])) largest_[c] = std::max(largest_[c], std::abs(row[c]));
      }
    }
  }
  const std::vector<double>& largest() const { return largest_; }

 private:
  std::vector<double> largest_;
};

// The events of one element by kind, in time order.
std::map<std::string, std::vector<double>> by_kind(const core::SlipMonitor& monitor) {
  std::map<std::string, std::vector<double>> kinds;
  for (const core::SlipEvent& e : monitor.events()) kinds[e.kind].push_back(e.time);
  return kinds;
}

AccuracyEstimate off(std::string reason) {
  AccuracyEstimate e;
  e.method = "off";
  e.reason = std::move(reason);
  return e;
}

}  // namespace

double companion_cost_factor(const core::RunOptions& run) {
  return run.integrator == "rk4_adaptive" ? std::pow(100.0, 0.2) : 2.0;
}

AccuracyEstimate estimate_accuracy(scene::Scene& scene, const core::RunResult& result,
                                   const PredictedStepLimits& limits,
                                   const AccuracySettings& settings) {
  const core::RunOptions& run = scene.run;
  const double expected = companion_cost_factor(run) * result.wall_seconds;
  if (settings.mode == AccuracyMode::off) return off("--accuracy off");
  if (result.instability || result.interrupted) return off("the run did not finish");
  std::string why_on = "--accuracy on";
  if (settings.mode == AccuracyMode::automatic) {
    if (expected > settings.budget_seconds) {
      return off(format(
          "the companion run would cost about %.3g s (%.3g x the run), above the %g s budget of "
          "the default; --accuracy on forces it",
          expected, companion_cost_factor(run), settings.budget_seconds));
    }
    why_on = format(
        "on by default: the companion run was expected to cost %.3g s (%.3g x the run), "
        "within the %g s budget",
        expected, companion_cost_factor(run), settings.budget_seconds);
  }

  AccuracyEstimate estimate;
  estimate.reason = why_on;
  estimate.event_tolerance = settings.event_tolerance * run.duration;
  estimate.final_tolerance = settings.final_tolerance;
  core::RunOptions companion = run;
  // Sticks shorter than the run's own resolution are dropped in both runs alike, so that a
  // finer companion does not report sticks the run could not.
  companion.event_resolution = run.event_resolution >= 0.0 ? run.event_resolution : run.dt;
  double factor = 1.0;  // Richardson: the run's error is factor * (run - companion)
  if (run.integrator == "rk4_adaptive") {
    estimate.method = "tighter_tolerance";
    estimate.order = 4;
    companion.tolerance = run.tolerance / 100.0;
    estimate.companion_tolerance = companion.tolerance;
  } else {
    estimate.method = "richardson";
    estimate.order = core::make_stepper(run.integrator, 1, run.dt)->order();
    companion.dt = run.dt / 2.0;
    const double two_p = std::pow(2.0, estimate.order);
    factor = two_p / (two_p - 1.0);
  }
  estimate.companion_integrator = companion.integrator;
  estimate.companion_dt = companion.dt;
  // The companion is finer than the run, so the predicted limits never restrict it; they
  // are reported beside the estimate (a run above its chatter limit is where events differ).
  estimate.limits = limits;

  ScaleSink sink;
  const double cpu_start = thread_cpu_seconds();
  // By default the companion never costs more than the budget, whatever the prediction said
  // (an adaptive companion may take far more steps than expected): past it, it is abandoned and the
  // estimate is off.
  struct OverBudget {
    double reached = 0.0;
  };
  core::ProgressCallback guard;
  if (settings.mode == AccuracyMode::automatic) {
    const double duration = companion.duration;
    guard = [&, duration](double fraction) {
      if (thread_cpu_seconds() - cpu_start > settings.budget_seconds)
        throw OverBudget{fraction * duration};
    };
  }
  core::RunResult fine;
  try {
    fine = core::simulate(*scene.network, companion, guard, &sink);
  } catch (const OverBudget& over) {
    AccuracyEstimate abandoned =
        off(format("the companion run passed the %g s budget of the default at t = %.3g s of %g s; "
                   "--accuracy on forces it",
                   settings.budget_seconds, over.reached, companion.duration));
    abandoned.cpu_seconds = thread_cpu_seconds() - cpu_start;
    return abandoned;
  }
  estimate.cpu_seconds = thread_cpu_seconds() - cpu_start;
  if (fine.interrupted) {
    AccuracyEstimate stopped = off("interrupted");
    stopped.interrupted = true;
    stopped.cpu_seconds = estimate.cpu_seconds;
    return stopped;
  }
  if (fine.instability) {
    estimate.verdict = "unknown";
    estimate.reasons.push_back(
        format("the companion run went unstable at t = %.6g s", fine.instability->time) + " in '" +
        fine.instability->component + "'");
    return estimate;
  }

  const bool adaptive = run.integrator == "rk4_adaptive";
  const std::string run_setting =
      adaptive ? "tolerance " + text::shortest(run.tolerance) : "dt = " + text::shortest(run.dt) + " s";
  const std::string companion_setting =
      adaptive ? "tolerance " + text::shortest(companion.tolerance)
               : "dt = " + text::shortest(companion.dt) + " s";
  bool events_differ = false;
  for (const core::SlipHistory& h : result.slip_events) {
    ElementEvents element{h.component, {}};
    const core::SlipHistory* other = nullptr;
    for (const core::SlipHistory& f : fine.slip_events) {
      if (f.component == h.component) other = &f;
    }
    const auto mine = by_kind(h.monitor);
    const auto theirs = other != nullptr ? by_kind(other->monitor) : decltype(mine){};
    std::map<std::string, std::size_t> next;  // per kind, the index of the next event
    for (const core::SlipEvent& e : h.monitor.events()) {
      EventAccuracy a{e.kind, e.time, std::nullopt};
      const std::size_t i = next[e.kind]++;
      const auto it = theirs.find(e.kind);
      // With events dropped (SlipMonitor's bound) the kept ones need not pair up by index.
      if (it != theirs.end() && it->second.size() == mine.at(e.kind).size() &&
          h.monitor.dropped() == 0 && other->monitor.dropped() == 0) {
        a.error = factor * std::abs(e.time - it->second[i]);
      }
      element.events.push_back(a);
    }
    for (const std::string kind : {"stick", "slip", "open"}) {
      // All events, kept or not.
      const std::size_t na = h.monitor.count(kind);
      const std::size_t nb = other != nullptr ? other->monitor.count(kind) : 0;
      if (na != nb) {
        events_differ = true;
        estimate.reasons.push_back(h.component + ": events differ: " + std::to_string(na) + " " +
                                   kind + " at " + run_setting + ", " + std::to_string(nb) +
                                   " in the companion (" + companion_setting + ")");
      }
    }
    for (const EventAccuracy& a : element.events) {
      if (a.error && *a.error > estimate.event_tolerance) {
        estimate.reasons.push_back(h.component + ": " + a.kind +
                                   format(" at t = %.7g s has an estimated error of %.2g s, above "
                                          "%.2g s",
                                          a.time, *a.error, estimate.event_tolerance));
      }
    }
    estimate.events.push_back(std::move(element));
  }

  // Final values: the last row of each run (the same sample time: same duration and rate).
  const core::Trajectory& tr = result.trajectory;
  const core::Trajectory& ft = fine.trajectory;
  std::map<std::string, double> signal_scale;
  const std::vector<double>& largest = sink.largest();
  for (int c = 1; c < ft.column_count() && c < static_cast<int>(largest.size()); ++c) {
    double& s = signal_scale[signal_of(ft.columns()[c])];
    s = std::max(s, largest[c]);
  }
  std::vector<std::string> bodies;
  for (const auto& a : scene.network->admittances()) bodies.push_back(a->name() + ".");
  // A signal that stays at zero (a body that never turns: its w) has a scale of rounding
  // noise, against which any noise is "large": errors below 1e-9 of the largest scale of the
  // body's signals are rounding, not inaccuracy.
  const auto rounding_of = [&](const std::string& column) {
    double body_scale = 0.0;
    for (const std::string& b : bodies) {
      if (column.compare(0, b.size(), b) != 0) continue;
      for (const auto& [signal, s] : signal_scale) {
        if (signal.compare(0, b.size(), b) == 0) body_scale = std::max(body_scale, s);
      }
    }
    return 1e-9 * body_scale;
  };
  bool finals_off = false;
  if (tr.row_count() > 0 && ft.row_count() > 0 && tr.column_count() == ft.column_count()) {
    const int last = tr.row_count() - 1;
    const int fine_last = ft.row_count() - 1;
    for (int c = 1; c < tr.column_count(); ++c) {
      const std::string& column = tr.columns()[c];
      FinalAccuracy f;
      f.column = column;
      f.value = tr.at(last, c);
      f.error = factor * std::abs(f.value - ft.at(fine_last, c));
      f.scale = signal_scale[signal_of(column)];
      f.judged = std::any_of(bodies.begin(), bodies.end(), [&](const std::string& b) {
        return column.compare(0, b.size(), b) == 0;
      });
      if (f.judged && f.error > settings.final_tolerance * f.scale + rounding_of(column)) {
        finals_off = true;
        estimate.reasons.push_back(column + format(" = %.7g has an estimated error of %.2g, above "
                                                   "%g of its scale %.3g",
                                                   f.value, f.error, settings.final_tolerance,
                                                   f.scale));
      }
      estimate.finals.push_back(f);
    }
  }
  const bool times_off =
      std::any_of(estimate.events.begin(), estimate.events.end(), [&](const ElementEvents& e) {
        return std::any_of(e.events.begin(), e.events.end(), [&](const EventAccuracy& a) {
          return a.error && *a.error > estimate.event_tolerance;
        });
      });
  estimate.verdict = events_differ || finals_off || times_off ? "inaccurate" : "accurate";
  return estimate;
}

nlohmann::ordered_json accuracy_json(const AccuracyEstimate& e) {
  using json = nlohmann::ordered_json;
  json j;
  j["method"] = e.method;
  if (e.method == "off") {
    j["reason"] = e.reason;
    return j;
  }
  j["order"] = e.order;
  j["companion"] = {
      {"integrator", e.companion_integrator},
      {"dt", e.companion_dt},
      {"tolerance", e.companion_tolerance ? json(*e.companion_tolerance) : json(nullptr)}};
  j["why"] = e.reason;
  if (e.limits.chatter_limit || e.limits.instability_limit) {
    const auto or_null = [](const std::optional<double>& v) {
      return v ? json(*v) : json(nullptr);
    };
    j["step_limits"] = {{"chatter", or_null(e.limits.chatter_limit)},
                        {"instability", or_null(e.limits.instability_limit)}};
  }
  j["tolerances"] = {{"event_time", e.event_tolerance}, {"final_relative", e.final_tolerance}};
  json events = json::object();
  for (const ElementEvents& element : e.events) {
    json list = json::array();
    for (const EventAccuracy& a : element.events) {
      list.push_back({{"kind", a.kind},
                      {"time", a.time},
                      {"error", a.error ? json(*a.error) : json(nullptr)}});
    }
    io::append_member(events, element.element, std::move(list));
  }
  j["events"] = std::move(events);
  json finals = json::object();
  for (const FinalAccuracy& f : e.finals) {
    io::append_member(finals, f.column,
                      {{"value", f.value}, {"error", f.error}, {"scale", f.scale}, {"judged", f.judged}});
  }
  j["final"] = std::move(finals);
  j["verdict"] = e.verdict;
  j["reasons"] = e.reasons;
  j["cpu_seconds"] = e.cpu_seconds;
  return j;
}

void print_inaccurate(const std::string& scene_name, const core::RunOptions& run,
                      const AccuracyEstimate& estimate) {
  if (run.integrator == "rk4_adaptive") {
    std::fprintf(stderr, "warning: %s: the run is inaccurate with rk4_adaptive, tolerance %s:\n",
                 scene_name.c_str(), text::shortest(run.tolerance).c_str());
  } else {
    std::fprintf(stderr, "warning: %s: the run is inaccurate with %s, dt = %s s:\n",
                 scene_name.c_str(), run.integrator.c_str(), text::shortest(run.dt).c_str());
  }
  constexpr std::size_t kShown = 6;
  for (std::size_t i = 0; i < estimate.reasons.size() && i < kShown; ++i) {
    std::fprintf(stderr, "  %s\n", estimate.reasons[i].c_str());
  }
  if (estimate.reasons.size() > kShown) {
    std::fprintf(stderr, "  ... %zu more in summary.json accuracy.reasons\n",
                 estimate.reasons.size() - kShown);
  }
  // Not every scene has an accurate step (sphere_roll's micro-bounces change with any step):
  // point to where the trade is measured rather than promise one.
  std::fprintf(stderr,
               "  (try a smaller %s; `stiction study` measures the largest accurate one; see "
               "docs/accuracy.md)\n",
               run.integrator == "rk4_adaptive" ? "tolerance" : "step");
}

}  // namespace stiction::services
