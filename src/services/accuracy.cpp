#include "services/accuracy.hpp"

#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <limits>
#include <memory>
#include <unordered_map>

#include "core/integrator_traits.hpp"
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

// The event times of one element by kind, in time order.
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
  const core::IntegratorTraits& traits = core::integrator_traits(run.integrator);
  return traits.adaptive ? std::pow(100.0, 1.0 / traits.error_order) : 2.0;
}

core::RunOptions companion_options(const core::RunOptions& run) {
  core::RunOptions companion = run;
  // Sticks shorter than the run's own resolution are dropped in both runs alike, so that a
  // finer companion does not report sticks the run could not.
  companion.event_resolution = run.event_resolution >= 0.0 ? run.event_resolution : run.dt;
  if (core::is_adaptive(run.integrator)) {
    companion.tolerance = run.tolerance / 100.0;
  } else {
    companion.dt = run.dt / 2.0;
  }
  return companion;
}

namespace {
constexpr double kSafety = 2.0;
}  // namespace

ComparisonSetup companion_setup(const core::RunOptions& run, JudgeRule rule) {
  ComparisonSetup setup;
  setup.rule = std::move(rule);
  const bool adaptive = core::is_adaptive(run.integrator);
  if (!adaptive) {
    // Richardson's estimate of the run's error, 2^p / (2^p - 1) times the difference, is a
    // point estimate: about half the time below the truth. Error bars that hold take a
    // safety factor (Roache's grid convergence index: 3 with two grids, 1.25 with three);
    // 2 is what the calibration of docs/accuracy.md measured to put the estimate at or above
    // the true error of final values in 96% of the generated cases, within 10x in all.
    const double two_p = std::pow(2.0, core::integrator_traits(run.integrator).order);
    setup.final_factor = kSafety * two_p / (two_p - 1.0);
    // Event times converge at first order at worst (an onset found on a step boundary, even
    // under rk4): 2^1 / (2^1 - 1) bounds every order q >= 1 from above, by at most 2x.
    setup.event_factor = 2.0;
  }
  const core::RunOptions companion = companion_options(run);
  setup.run_label = adaptive ? "tolerance " + text::shortest(run.tolerance)
                             : "dt = " + text::shortest(run.dt) + " s";
  setup.other_label = adaptive ? "the companion (tolerance " + text::shortest(companion.tolerance) + ")"
                               : "the companion (dt = " + text::shortest(companion.dt) + " s)";
  return setup;
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
  estimate.rule = settings.rule ? *settings.rule : read_judge_rule(scene);
  const core::RunOptions companion = companion_options(run);
  const bool adaptive = core::is_adaptive(run.integrator);
  estimate.method = adaptive ? "tighter_tolerance" : "richardson";
  estimate.order = core::integrator_traits(run.integrator).order;
  if (adaptive) estimate.companion_tolerance = companion.tolerance;
  estimate.companion_integrator = companion.integrator;
  estimate.companion_dt = companion.dt;
  // The companion is finer than the run, so the predicted limits never restrict it; they
  // are reported beside the estimate (a run above its chatter limit is where events differ).
  estimate.limits = limits;

  MotionScales scales;
  {
    std::vector<std::string> columns{"t"};
    for (auto& c : scene.network->signal_columns()) columns.push_back(std::move(c));
    scales.set_columns(columns);
  }
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
    fine = core::simulate(*scene.network, companion, guard, &scales);
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

  ComparisonSetup setup = companion_setup(run, estimate.rule);
  setup.scales = &scales;
  estimate.comparison = compare_runs(*scene.network, result, fine, setup);
  const RunComparison& cmp = estimate.comparison;

  // Every event of the run with its estimate: the first and last of each kind as compared;
  // the others matched by index where the two runs have as many of that kind.
  // Linear in the elements: the companion's histories and the compared events by name.
  std::unordered_map<std::string, const core::SlipHistory*> fine_by_name;
  for (const core::SlipHistory& f : fine.slip_events) fine_by_name.emplace(f.component, &f);
  std::unordered_map<std::string, const ComparedQuantity*> compared_by_name;
  for (const ComparedQuantity& q : cmp.events) compared_by_name.emplace(q.name, &q);
  for (const core::SlipHistory& h : result.slip_events) {
    ElementEvents element{h.component, {}};
    const auto found = fine_by_name.find(h.component);
    const core::SlipHistory* other = found != fine_by_name.end() ? found->second : nullptr;
    const auto mine = by_kind(h.monitor);
    const auto theirs = other != nullptr ? by_kind(other->monitor) : decltype(mine){};
    std::map<std::string, std::size_t> next;  // per kind, the index of the next event
    for (const core::SlipEvent& e : h.monitor.events()) {
      EventAccuracy a{e.kind, e.time, std::nullopt, e.uncertainty, false};
      const std::size_t i = next[e.kind]++;
      const std::size_t n = mine.at(e.kind).size();
      const ComparedQuantity* compared = nullptr;
      for (const auto& [index, which] : {std::pair{std::size_t{0}, "first_"}, {n - 1, "last_"}}) {
        const auto q = compared_by_name.find(h.component + "." + which + e.kind);
        if (i == index && q != compared_by_name.end()) compared = q->second;
      }
      const auto it = theirs.find(e.kind);
      if (compared != nullptr) {
        a.error = compared->error;
        a.judged = compared->judged;
      } else if (it != theirs.end() && it->second.size() == n && h.monitor.dropped() == 0 &&
                 other->monitor.dropped() == 0) {
        // With events dropped (SlipMonitor's bound) the kept ones need not pair up by index.
        a.error = std::max(setup.event_factor * std::abs(e.time - it->second[i]), e.uncertainty);
      }
      element.events.push_back(a);
    }
    estimate.events.push_back(std::move(element));
  }
  for (const ComparedQuantity& q : cmp.finals) {
    FinalAccuracy f;
    f.column = q.name;
    f.value = q.value;
    f.error = q.error.value_or(std::numeric_limits<double>::quiet_NaN());
    f.scale = q.scale;
    f.judged = q.judged;
    estimate.finals.push_back(f);
  }
  estimate.reasons.insert(estimate.reasons.end(), cmp.reasons.begin(), cmp.reasons.end());
  estimate.verdict = cmp.accurate() ? "accurate" : "inaccurate";
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
  // The rule (docs/accuracy.md, "What is judged"): the classes judged, the exceptions and
  // the relative tolerances, then the quantities the verdict rests on.
  json classes = json::array();
  for (const std::string& c : quantity_classes()) {
    if (e.rule.classes.count(c) != 0) classes.push_back(c);
  }
  json tolerances = json::object();
  for (const std::string& c : quantity_classes()) tolerances[c] = e.rule.tolerance(c);
  j["rule"] = {{"classes", classes},
               {"judge", e.rule.judge},
               {"ignore", e.rule.ignore},
               {"tolerances", tolerances},
               {"event_time_scale",
                "the longer of the times since the previous and to the next event of its "
                "kind (docs/accuracy.md)"}};
  j["judged"] = e.comparison.judged;
  json not_converged = json::array();
  for (const CountDifference& d : e.comparison.not_converged) {
    not_converged.push_back({{"element", d.component},
                             {"kind", d.kind},
                             {"run", d.run},
                             {"companion", d.other},
                             {"judged", d.judged}});
  }
  j["not_converged"] = std::move(not_converged);
  json compared = json::array();
  for (const ComparedQuantity& q : e.comparison.events) {
    compared.push_back({{"name", q.name},
                        {"class", q.cls},
                        {"time", q.value},
                        {"companion", std::isnan(q.other) ? json(nullptr) : json(q.other)},
                        {"error", q.error ? json(*q.error) : json(nullptr)},
                        {"located", q.located},
                        {"tolerance", q.tolerance},
                        {"judged", q.judged},
                        {"note", q.note}});
  }
  j["compared_events"] = std::move(compared);
  json events = json::object();
  for (const ElementEvents& element : e.events) {
    json list = json::array();
    for (const EventAccuracy& a : element.events) {
      list.push_back({{"kind", a.kind},
                      {"time", a.time},
                      {"error", a.error ? json(*a.error) : json(nullptr)},
                      {"located", a.located},
                      {"judged", a.judged}});
    }
    io::append_member(events, element.element, std::move(list));
  }
  j["events"] = std::move(events);
  json finals = json::object();
  for (const FinalAccuracy& f : e.finals) {
    io::append_member(finals, f.column,
                      {{"value", f.value},
                       {"error", std::isfinite(f.error) ? json(f.error) : json(nullptr)},
                       {"scale", f.scale},
                       {"judged", f.judged}});
  }
  j["final"] = std::move(finals);
  j["verdict"] = e.verdict;
  j["reasons"] = e.reasons;
  j["cpu_seconds"] = e.cpu_seconds;
  return j;
}

void print_inaccurate(const std::string& scene_name, const core::RunOptions& run,
                      const AccuracyEstimate& estimate) {
  if (core::is_adaptive(run.integrator)) {
    std::fprintf(stderr, "warning: %s: the run is inaccurate with %s, tolerance %s:\n",
                 scene_name.c_str(), run.integrator.c_str(), text::shortest(run.tolerance).c_str());
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
               core::is_adaptive(run.integrator) ? "tolerance" : "step");
}

}  // namespace stiction::services
