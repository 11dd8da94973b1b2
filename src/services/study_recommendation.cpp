// The study's closing recommendation: the cheapest run that meets the accuracy target. Each
// integrator's candidate is its run within the target with the fewest network evaluations
// (exact: its largest accurate step or loosest accurate tolerance); among those, the
// integrators are compared by CPU time, since a step costs more than its evaluations (the
// event detection, the monitors and the rows cost per step: on a single body a step of
// symplectic_euler, one evaluation, costs about 0.6x one of rk4, four).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "services/study.hpp"

namespace stiction::services {
namespace {

bool is_adaptive(const StudyRow& row) { return row.tolerance > 0.0; }

// A row within the target counts only when every finer run of its integrator (smaller step,
// tighter tolerance) is within the target too: a coarse step that happens to land on the
// reference between two that do not is luck, not a setting to recommend.
bool finer_rows_meet(const StudyResult& r, const StudyRow& row) {
  for (const auto& other : r.rows) {
    if (other.integrator != row.integrator) continue;
    const bool finer = is_adaptive(row) ? other.tolerance < row.tolerance : other.dt < row.dt;
    if (finer && !other.meets_target) return false;
  }
  return true;
}

const StabilityLimit* limit_for(const StudyResult& r, const std::string& integrator) {
  for (const auto& limit : r.limits) {
    if (limit.integrator == integrator) return &limit;
  }
  return nullptr;
}

}  // namespace

double largest_accurate_tolerance(const StudyResult& r, const std::string& integrator) {
  double largest = 0.0;
  for (const auto& row : r.rows) {
    if (row.integrator == integrator && is_adaptive(row) && row.meets_target &&
        finer_rows_meet(r, row)) {
      largest = std::max(largest, row.tolerance);
    }
  }
  return largest;
}

std::vector<Recommendation> recommendation_candidates(const StudyResult& r) {
  std::vector<Recommendation> best;  // one per integrator, in the order of the rows
  auto consider = [&best](const Recommendation& c) {
    for (auto& b : best) {
      if (b.integrator != c.integrator) continue;
      if (c.evaluations_per_second < b.evaluations_per_second) b = c;
      return;
    }
    best.push_back(c);
  };
  for (const auto& row : r.rows) {
    if (!row.meets_target) continue;
    const StabilityLimit* limit = is_adaptive(row) ? nullptr : limit_for(r, row.integrator);
    // With a bisected accuracy limit, that limit decides (it also knows the bisection's runs).
    if (limit != nullptr ? !(row.dt <= limit->accurate) : !finer_rows_meet(r, row)) continue;
    Recommendation c;
    c.integrator = row.integrator;
    c.dt = row.dt;
    c.tolerance = row.tolerance;
    c.evaluations_per_second = static_cast<double>(row.evaluations) / r.duration;
    c.cpu_per_second = row.cpu_seconds / r.duration;
    c.event_time_error = row.event_time_error;
    c.final_value_error = row.final_value_error;
    consider(c);
  }
  for (const auto& limit : r.limits) {
    if (!(limit.accurate > 0.0) || !limit.accurate_bisected) continue;
    Recommendation c;
    c.integrator = limit.integrator;
    c.dt = limit.accurate;
    c.evaluations_per_second = static_cast<double>(limit.accurate_evaluations) / r.duration;
    c.cpu_per_second = limit.accurate_cpu_seconds / r.duration;
    c.event_time_error = limit.accurate_event_time_error;
    c.final_value_error = limit.accurate_final_value_error;
    c.bisected = true;
    consider(c);
  }
  return best;
}

Recommendation cheapest(const std::vector<Recommendation>& candidates) {
  Recommendation best;
  for (const auto& c : candidates) {
    if (best.integrator.empty() || c.cpu_per_second < best.cpu_per_second ||
        (c.cpu_per_second == best.cpu_per_second &&
         c.evaluations_per_second < best.evaluations_per_second)) {
      best = c;
    }
  }
  return best;
}

}  // namespace stiction::services
