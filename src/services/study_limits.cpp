#include "services/study_limits.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/integrator_traits.hpp"
#include "core/stability.hpp"
#include "services/pilot.hpp"
#include "sys/interrupt.hpp"

namespace stiction::services {
namespace {

std::string format_g(double value, int digits = 3) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

}  // namespace

void StepLimitSearch::note(const std::string& text) {
  result_.notes.push_back(text);
  if (log_) log_(text);
}

const StudyProbe& StepLimitSearch::probe(const std::string& integrator, double h, int& runs) {
  const auto key = std::make_pair(integrator, h);
  if (const auto found = probes_.find(key); found != probes_.end()) return found->second;
  ++runs;
  return probes_.emplace(key, run_(integrator, h)).first->second;
}

// What `stiction check` predicts, with its functions and its pilot run (bounded in steps),
// so that the study's predicted limits are check's.
void StepLimitSearch::predict(scene::Scene& scene, const std::vector<std::string>& integrators) {
  const Pilot pilot = bounded_pilot(*scene.network, scene.run);
  if (log_) {
    log_("predicted limits: sampling " + std::to_string(options_.stability_samples) +
         " states per regime (" + scene.run.integrator + ", dt = " + format_g(scene.run.dt) +
         (pilot.shortened ? ", first " + format_g(pilot.options.duration) + " s" : std::string()) +
         ")");
  }
  if (pilot.shortened) {
    note("predicted limits from the first " + format_g(pilot.options.duration) + " s of " +
         format_g(scene.run.duration) + " s (the pilot run's step budget, as `stiction check`)");
  }
  const auto states = core::sample_states(*scene.network, pilot.options, options_.stability_samples);
  if (sys::interrupted()) throw sys::Interrupted{};
  for (const auto& integrator : integrators) {
    if (core::is_adaptive(integrator)) continue;
    StabilityLimit limit;
    limit.integrator = integrator;
    const core::StepLimit predicted = core::predict_step_limit(
        *scene.network, integrator, states, 1e-9, 1.0, &sys::interrupt_flag());
    if (sys::interrupted()) throw sys::Interrupted{};
    if (predicted.skipped) {  // too many states for the dense analysis: no prediction
      limit.predicted_skipped = true;
      note("predicted limits of " + integrator +
           ": skipped: the network's largest island (bodies its elements couple) has " +
           std::to_string(core::largest_island_states(*scene.network)) + " states, more than the " +
           std::to_string(core::kMaxAnalysedStates) +
           " the step analysis linearizes (docs/limits.md); the grid is the scene's dt x 8, 4, "
           "2, ...");
    }
    limit.predicted = predicted.max_step;
    limit.predicted_unbounded = predicted.unbounded;
    limit.predicted_time = predicted.limiting_time;
    limit.chatter_free = predicted.chatter_free_step;
    if (!predicted.skipped && log_) {
      log_("predicted " + integrator + ": unstable above " + format_g(limit.predicted, 4) +
           " s, stuck friction chatters above " + format_g(limit.chatter_free, 4) + " s");
    }
    result_.limits.push_back(limit);
  }
}

// The accuracy need not be monotone in the step (a stick inside an impact moves with the
// impact's timing): the answer is a step within the target with every known step below it
// within the target too, and a known step within the bisection's precision above it outside.
void StepLimitSearch::bisect_accurate(StabilityLimit& limit) {
  const std::string& integrator = limit.integrator;
  struct Known {
    double h;
    bool meets;
    std::string failure;
  };
  std::vector<Known> known;
  for (const auto& row : result_.rows) {
    if (row.integrator == integrator) known.push_back({row.dt, row.meets_target, row.accuracy_failure});
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
      const StudyProbe& p = probe(integrator, mid, limit.accuracy_runs);
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
  const StudyRow* row = nullptr;
  for (const auto& r : result_.rows) {
    if (r.integrator == integrator && r.dt == lo) row = &r;
  }
  const auto found = probes_.find(std::make_pair(integrator, lo));
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

void StepLimitSearch::bisect_stable(StabilityLimit& limit, double scene_dt) {
  const std::string& integrator = limit.integrator;
  const auto stable = [&](double h) { return probe(integrator, h, limit.runs).stable; };
  double lo = 0.0, hi = std::numeric_limits<double>::infinity();
  for (const auto& row : result_.rows) {
    if (row.integrator == integrator && row.status == "unstable") hi = std::min(hi, row.dt);
  }
  for (const auto& row : result_.rows) {
    if (row.integrator == integrator && row.status == "ok" && row.dt < hi) lo = std::max(lo, row.dt);
  }
  const double longest = result_.duration / 4.0;
  if (!std::isfinite(hi)) {
    double h = lo > 0.0 ? lo : scene_dt;
    for (;;) {
      h *= 2.0;
      if (h > longest) {
        limit.bisected = lo;
        limit.note = "stable at every step tried, up to " + format_g(lo) + " s";
        return;
      }
      if (!stable(h)) {
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
      if (stable(h)) {
        lo = h;
        break;
      }
      hi = h;
      const double took =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
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
    if (stable(mid)) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  limit.bisected = lo;
  limit.unstable_above = hi;
}

}  // namespace stiction::services
