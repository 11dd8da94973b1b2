#include "core/run_limits.hpp"

#include <cmath>
#include <cstdio>

#include "core/integrator_traits.hpp"

namespace stiction::core {
namespace {

std::string format(double v) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

}  // namespace

std::optional<LimitViolation> check_run_limits(const RunOptions& o) {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive(o.dt)) return LimitViolation{"dt", "must be a finite number > 0 (got " + format(o.dt) + ")"};
  if (!positive(o.duration)) {
    return LimitViolation{"duration", "must be a finite number > 0 (got " + format(o.duration) + ")"};
  }
  if (!positive(o.output_rate)) {
    return LimitViolation{"output_rate",
                          "must be a finite number > 0 (got " + format(o.output_rate) + ")"};
  }
  if (is_adaptive(o.integrator) && !positive(o.tolerance)) {
    return LimitViolation{"tolerance", "must be a finite number > 0 (got " + format(o.tolerance) + ")"};
  }
  // A local error bound below the rounding of a double (about 1e-16 of a state of order 1)
  // cannot be met by any step: the step would shrink until it underflows.
  if (is_adaptive(o.integrator) && o.tolerance < RunLimits::kMinTolerance) {
    return LimitViolation{"tolerance", "must be at least " + format(RunLimits::kMinTolerance) +
                                           " (got " + format(o.tolerance) +
                                           "): no step meets a local error below the rounding of "
                                           "double precision"};
  }
  // Computed in floating point: duration / dt may be far beyond any integer type.
  const double steps = std::ceil(o.duration / o.dt);
  if (!is_adaptive(o.integrator) && !(steps <= RunLimits::kMaxSteps)) {
    return LimitViolation{"dt", "duration / dt = " + format(o.duration) + " / " + format(o.dt) +
                                    " = " + format(steps) + " steps, more than the limit of " +
                                    format(RunLimits::kMaxSteps) + " (docs/limits.md)"};
  }
  const double rows = std::floor(o.duration * o.output_rate) + 1.0;
  if (!(rows <= RunLimits::kMaxRows)) {
    return LimitViolation{"output_rate", "duration * output_rate = " + format(o.duration) + " * " +
                                             format(o.output_rate) + " gives " + format(rows) +
                                             " rows, more than the limit of " +
                                             format(RunLimits::kMaxRows) + " (docs/limits.md)"};
  }
  return std::nullopt;
}

std::optional<LimitViolation> check_user_run(const RunOptions& o) {
  if (auto violation = check_run_limits(o)) return violation;
  // A fixed step longer than the run used to become one step of the duration, silently; at
  // dt = 1e308 the friction laws, which take the step as a parameter, gave NaN forces.
  if (!is_adaptive(o.integrator) && o.dt > o.duration) {
    return LimitViolation{"dt", "the step " + format(o.dt) + " s is longer than the run (duration = " +
                                    format(o.duration) + " s): give a step <= the duration"};
  }
  // At least two rows (t = 0 and one more): one row is the initial state only, and a run
  // that writes it and ends `ok` looks complete (issue 25: output_rate = 0.1, duration = 2).
  if (!(std::floor(o.duration * o.output_rate + 1e-9) + 1.0 >= 2.0)) {
    return LimitViolation{"output_rate", "duration * output_rate = " + format(o.duration) + " * " +
                                             format(o.output_rate) +
                                             " < 1 writes only the row at t = 0; give an output_rate "
                                             ">= 1 / duration = " + format(1.0 / o.duration) +
                                             " (or a longer duration)"};
  }
  return std::nullopt;
}

long expected_rows(const RunOptions& o) {
  return static_cast<long>(std::floor(o.duration * o.output_rate + 1e-9)) + 1;
}

}  // namespace stiction::core
