// Bounds on what a run may ask for, checked in floating point before any count is converted
// to an integer, any buffer is sized or any loop starts: a huge duration, a tiny step or a
// huge output rate must be refused up front rather than overflow a step counter (the run
// would stop after one step and look complete) or ask for terabytes. docs/limits.md lists
// every bound and why it is where it is.
#pragma once

#include <optional>
#include <string>

#include "core/simulation.hpp"

namespace stiction::core {

struct RunLimits {
  // Fixed steps per run: 1e11 steps is about a day of computing for the smallest scene, and
  // far below 2^53, so step counts and times computed from them stay exact.
  static constexpr double kMaxSteps = 1e11;
  // Rows of trajectory.csv: 1e8 rows is about 2e9 bytes of CSV per column.
  static constexpr double kMaxRows = 1e8;
  // rk4_adaptive's smallest tolerance: below it the local error is the state's rounding.
  static constexpr double kMinTolerance = 1e-15;
};

// What is wrong with the run's numbers, naming the option (`dt`, `duration`, `output_rate`)
// to blame, or nothing. Non-finite and non-positive values are wrong too.
struct LimitViolation {
  std::string key;
  std::string message;
};
std::optional<LimitViolation> check_run_limits(const RunOptions& options);
// check_run_limits, and what only a user's run must meet (issue 25): a fixed step no longer
// than the run, and at least two rows. Not applied inside core::simulate: a step check's
// trial or pilot runs over a short stretch at the scene's output rate, and may write one row.
std::optional<LimitViolation> check_user_run(const RunOptions& options);

// Rows a run writes (t = 0 included), computed as simulate() does; only meaningful when
// check_run_limits found nothing.
long expected_rows(const RunOptions& options);

}  // namespace stiction::core
